"""The kernel's work budgets: every constant and cost formula in one place, and
the one account of a whole certificate.

Two limits, both in *word operations* (about one machine-word integer
operation each; measured on the 2-core reference machine, shared and loaded,
3 to 8 x 10^7 of them per second of pure-Python work):

* per computation: a single exact computation (a rebuild of D and N, a
  pseudo-remainder sequence, the pieces of a pruning test...) is priced before
  it runs and rejected over its own limit (WORK_BUDGET; STURM_BUDGET for a
  pseudo-remainder sequence, in degree^4 bits^2; PIECES_BUDGET for the pruning
  pieces in u) -- so no single step can run for minutes;
* per certificate: :func:`check` opens one :class:`Account` of
  CERTIFICATE_BUDGET word operations.  Every priced computation is charged to
  it when it is priced (:func:`within_budget`), and the kernel's open-ended
  loops -- pseudo-remainder steps (gcds, Sturm sequences, squarefree parts),
  Descartes tests, exact values and signs at rationals (so bisections of
  algebraic numbers), products of rational polynomials, generator-facet
  conditions, adjacency tests, edge-walk steps, pruning slot tests -- charge
  their cost, by the sizes of their numbers, as they run (:func:`charge`).  Once the account is
  overdrawn the claim being checked is rejected ("over the certificate's work
  budget"), and, since the kernel stops at the first rejected claim, so is the
  certificate.  Many claims each just under the per-computation limit cannot
  add up to more than one certificate budget.

The constants and the cost formulas of the primitive operations are here.  The
estimate of a specific computation's size stays next to that computation
(conditions.rebuild_size, claims_radius.scan_cost, tie.interpolation_cost,
pruning.pieces_cost, pruning_rational.pieces_cost, ellipsoids._conditions_cost,
boxes._price) and is passed to :func:`within_budget`.

Charges are deterministic (counts of operations, never clocks), so a verdict
does not depend on the machine's load.  Behind them stands one safety net, a
clock: an account also has a time limit (TIME_LIMIT seconds of the process's
CPU time by default -- CPU time, so that other processes' load does not count),
and a charge made after it rejects the claim ("over the kernel's time limit").  It
can only turn a verdict into a rejection -- never accept -- and it guarantees
a verdict within about that time even where the cost formulas misprice some
work.  Genuine certificates stay far below both limits.  Outside
:func:`account` (a kernel function called directly, e.g. by a test) charges
are not counted.
"""

from contextlib import contextmanager
from contextvars import ContextVar
from time import process_time

from .failure import require

WORK_BUDGET = 10**8  # word operations of one priced computation: one to three seconds of work
FRACTION_WEIGHT = 100  # word operations per Fraction operation on short numbers
PYTHON_OP = 10  # word operations per interpreted integer operation on short numbers (its overhead)
DISK_STEP = 50000  # word operations per term of one step of the Bernstein positivity proof (disk arithmetic)
CALL = 1000  # word operations of the fixed overhead of one Descartes test
STURM_BUDGET = 5 * 10**12  # degree^4 bits^2 of one pseudo-remainder sequence (gcd, Sturm): up to about 20 s
STURM_WORDS = 1000  # degree^4 bits^2 per metered word operation of a Sturm sequence (measured: 880 at degree 80)
DESCARTES_BUDGET = 40 * STURM_BUDGET  # degree^4 bits^2 of one Descartes isolation (polys.isolate): its nodes are charged
# to the certificate's account as they run (and the clock stands behind them), so this up-front gate only keeps absurd
# sizes out; at the Sturm gate a genuine radius certificate (binding d_39 of degree 120, 426-bit coefficients: 7.9e12)
# was rejected though its isolation takes about 4 s
PIECES_BUDGET = 20 * WORK_BUDGET  # the estimate of the Bernstein pieces of a pruning test in u
PIECES_PER_WORD = 5  # that estimate runs about 7 times faster than word operations (a genuine Pade(6,6) record: 7e8, 1 s)
CERTIFICATE_BUDGET = 20 * WORK_BUDGET  # everything one certificate may cost: 25-60 s (genuine ones: < 5e8)
BIG_CHARGE = 10**6  # a charge this large reads the clock itself (else every 64th: 63 priced computations of up
# to WORK_BUDGET each, mispriced a few times, would run minutes between two readings)
TIME_LIMIT = 50  # CPU seconds: the clock behind the account (a verdict within a minute of the kernel's own work)


class Account:
    """The running total of one certificate's work, in word operations."""

    __slots__ = ("limit", "spent", "memo", "deadline", "time_limit", "charges")

    def __init__(self, limit=CERTIFICATE_BUDGET, time_limit=TIME_LIMIT):
        self.limit, self.spent, self.memo, self.charges = limit, 0, {}, 0
        self.time_limit = time_limit
        self.deadline = None if time_limit is None else process_time() + time_limit

    def __repr__(self):
        return f"Account(spent={self.spent:.3e}, limit={self.limit:.0e})"


_CURRENT = ContextVar("exactinv_check_account", default=None)


@contextmanager
def account(limit=CERTIFICATE_BUDGET, time_limit=TIME_LIMIT):
    """Open the account of one certificate: every charge inside goes to it (time_limit None: no clock)."""
    acc = Account(limit, time_limit)
    token = _CURRENT.set(acc)
    try:
        yield acc
    finally:
        _CURRENT.reset(token)


def active():
    """Is an account open?  (Callers skip working out a cost when none is.)"""
    return _CURRENT.get() is not None


def charge(cost, what):
    """Charge ``cost`` word operations to the open account; reject once it is overdrawn."""
    acc = _CURRENT.get()
    if acc is not None:
        acc.spent += cost
        if acc.spent > acc.limit:
            require(False, f"over the certificate's work budget: {what} brings the certificate's estimated work "
                    f"to {acc.spent:.2e} word operations > {acc.limit:.0e}")
        acc.charges += 1
        if acc.deadline is not None and (not acc.charges & 63 or cost >= BIG_CHARGE) and process_time() > acc.deadline:
            require(False, f"over the kernel's time limit: no verdict after {acc.time_limit} s of CPU time ({what} was next)")


def memo(key, compute):
    """compute(), remembered in the open account under ``key``: a result shared between claims
    (a squarefree part, a proved radius) is computed and charged once per certificate."""
    acc = _CURRENT.get()
    if acc is None:
        return compute()
    if key not in acc.memo:
        acc.memo[key] = compute()
    return acc.memo[key]


def affordable(cost):
    """Would ``cost`` more word operations still fit in the open account?"""
    acc = _CURRENT.get()
    return acc is None or acc.spent + cost <= acc.limit


def within_budget(cost, what, limit=WORK_BUDGET):
    """Reject (never run) a computation whose estimated cost exceeds ``limit`` or what is left of
    the certificate's account; otherwise charge it: a certificate must not make the kernel work
    for minutes before its verdict."""
    require(cost <= limit, f"over the kernel's work budget: {what} (estimated {cost:.2e} word "
            f"operations > {limit:.0e})")
    charge(cost, what)


# ------------------------------------------------------------------ cost formulas
def words(bits):
    """Machine words of a bits-bit integer (at least one)."""
    return 1 + bits // 64


def sturm_cost(degree, bits):
    """degree^4 bits^2: the price of a pseudo-remainder sequence (gcd with the derivative, Sturm
    sequence) of a degree-``degree`` integer polynomial with ``bits``-bit coefficients."""
    return degree ** 4 * bits ** 2


def within_sturm_budget(degree, bits, what):
    """Reject, before it starts, a pseudo-remainder sequence over STURM_BUDGET or over what is left
    of the certificate's account (its steps charge their actual cost as they run)."""
    cost = sturm_cost(degree, bits)
    require(cost <= STURM_BUDGET, f"over the kernel's work budget: {what} of a polynomial of degree {degree} "
            f"with {bits}-bit coefficients (degree^4 bits^2 > {STURM_BUDGET:.0e})")
    require(affordable(cost // STURM_WORDS), f"over the certificate's work budget: {what} of a polynomial of "
            f"degree {degree} with {bits}-bit coefficients (estimated {cost // STURM_WORDS:.2e} word operations "
            "more than the certificate has left)")


def remainder_step_cost(length, lead_bits, other_bits):
    """One reduction step of a pseudo-remainder: a polynomial of ``length`` coefficients multiplied
    and reduced, its content removed (gcds, quadratic in the words)."""
    w = words(lead_bits + other_bits)
    return length * (PYTHON_OP + w * (4 + w))


def descartes_node_cost(degree, bits, end_bits=0):
    """One Descartes test (a Moebius transform and a Taylor shift): about 2 degree^2 products and
    additions of numbers of up to ``bits`` bits (the coefficients' plus degree times the ends'), the
    degree^2 / 2 products of the Horner step each by a number of ``end_bits`` bits (quadratic in words)."""
    w = words(bits)
    return CALL + 2 * (degree + 1) ** 2 * (PYTHON_OP + w) + (degree + 1) ** 2 * w * words(end_bits) // 2


def fraction_products_cost(count, bits):
    """``count`` Fraction products and sums of numbers of about ``bits`` bits (each normalised by gcds,
    quadratic in the words)."""
    w = words(bits)
    return count * (FRACTION_WEIGHT + 2 * w * w)


def condition_cost(terms, n, d_terms):
    """One generator-facet condition: g_j N_k w for ``terms`` coefficient matrices in dimension n, times
    D (``d_terms`` coefficients), made coprime (measured: 40-90 us each at degree 2)."""
    return 1000 + 2 * PYTHON_OP * terms * (n + 2 * d_terms)


def modular_squarefree_cost(degree, bits):
    """A gcd of p and p' modulo a prime: the reduction of the coefficients, then degree^2 small operations."""
    return (degree + 1) * words(bits) + 4 * (degree + 1) ** 2


def disk_step_cost(terms):
    """One step (or one step-size trial) of the Bernstein positivity proof (exactinv_check.bernstein): a few
    operations on 128-bit disks per term b_{k,m} t^(m-1) e^(-z_k t) (``terms`` of them in all); measured about
    1 ms of work per term and step at degree 15."""
    return DISK_STEP * terms


def evaluation_cost(degree, bits, end_bits=0):
    """One exact value of a degree-``degree`` polynomial with ``bits``-bit coefficients at a rational of
    ``end_bits``-bit numerator and denominator (Horner: each step multiplies a number growing to
    bits + degree end_bits bits by one of end_bits bits)."""
    return (degree + 1) * (PYTHON_OP + words(bits + degree * end_bits) * words(end_bits))


def sparse_read_cost(entries, longest_chars):
    """Reading ``entries`` nonzero entries of a sparse matrix (version 3), each a number string of at most
    ``longest_chars`` characters: a regular-expression match and a Fraction each (decimal-to-binary
    conversion, quadratic in the words)."""
    w = words(4 * longest_chars)
    return entries * (FRACTION_WEIGHT + 2 * w * w)
