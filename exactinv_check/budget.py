"""The kernel's work budgets: every constant and cost formula in one place, and
the one account of a whole certificate.

Two limits, both in *word operations* (a unit of work calibrated to RATE =
10^8 of them per CPU second on the 2-core reference machine, shared and
loaded: benchmarks/kernel_cost_model.py measures every charged primitive --
Descartes tests, signs at rationals, pseudo-remainder sequences, isolations,
the tail proof -- and each charges within about 3x of that rate):

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

from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar
from time import process_time
from typing import Any, Callable, Iterator, Sequence

from .failure import require_budget

RATE = 10**8  # charged word operations per CPU second of the kernel's real work on the reference machine (shared, loaded):
# every cost formula below is calibrated to it within about 3x by benchmarks/kernel_cost_model.py (benchmarks/README.md)
WORK_BUDGET = 10**8  # word operations of one priced computation: one to three seconds of work
FRACTION_WEIGHT = 100  # word operations per Fraction operation on short numbers
PYTHON_OP = 10  # word operations per interpreted integer operation on short numbers (its overhead)
DISK_STEP = 50000  # word operations per term of one step of the Bernstein positivity proof (disk arithmetic)
CALL = 3000  # word operations of the fixed overhead of one Descartes test (measured: about 30 us)
STURM_BUDGET = 5 * 10**12  # degree^4 bits^2 of one pseudo-remainder sequence (gcd, Sturm): up to about 20 s
STURM_WORDS = 1000  # degree^4 bits^2 per metered word operation of a Sturm sequence (measured: 880 at degree 80)
SCAN_BUDGET = 20 * WORK_BUDGET  # the estimate of the radius's coefficient polynomials d_0 .. d_(N-1) (claims_radius):
# measured 2.6 s of CPU for 77 of them at 1.7e8 (a genuine certificate of the random tie family, tail index 77); an
# up-front gate on absurd sizes only (the estimate is the former Fraction algorithm's, 2-3x high; the Kronecker
# products are charged as they run): at 5e8 a genuine line-irrational radius (d_0 .. d_79 estimated 1.35e9, charged
# 5.3e8 in 3.9 s) was refused (issue 22)
DESCARTES_BUDGET = 16 * STURM_BUDGET  # degree^4 bits^2 of one Descartes isolation (polys.isolate): its nodes are charged
# to the certificate's account as they run (and the clock stands behind them), so this up-front gate only keeps absurd
# sizes out; at the Sturm gate a genuine radius certificate (binding d_39 of degree 120, 426-bit coefficients)
# was rejected though its isolation takes about 4 s (3.8e13); 16x keeps the red team's degree-127, 670-bit H3 (1.2e14) out
PIECES_BUDGET = 20 * WORK_BUDGET  # the estimate of the Bernstein pieces of a pruning test in u
PIECES_PER_WORD = 5  # that estimate runs about 7 times faster than word operations (a genuine Pade(6,6) record: 7e8, 1 s)
CERTIFICATE_BUDGET = 40 * WORK_BUDGET  # everything one certificate may cost: about 40 s at RATE (the clock, TIME_LIMIT,
# stands behind it); genuine ones measured up to 2e9 (a radius of degree 272, an LP-route Pade(2,2) set on R^10/40)
BIG_CHARGE = 10**6  # a charge this large reads the clock itself (else every 64th: 63 priced computations of up
# to WORK_BUDGET each, mispriced a few times, would run minutes between two readings)
TIME_LIMIT = 50  # CPU seconds: the clock behind the account (a verdict within a minute of the kernel's own work)


class Account:
    """The running total of one certificate's work, in word operations."""

    __slots__ = ("limit", "spent", "memo", "deadline", "time_limit", "charges")

    def __init__(self, limit: Any = CERTIFICATE_BUDGET, time_limit: Any = TIME_LIMIT) -> None:
        self.limit, self.spent, self.charges = limit, 0, 0
        self.memo: dict[Any, Any] = {}
        self.time_limit = time_limit
        self.deadline = None if time_limit is None else process_time() + time_limit

    def __repr__(self) -> Any:
        return f"Account(spent={self.spent:.3e}, limit={self.limit:.0e})"


_CURRENT = ContextVar("exactinv_check_account", default=None)


@contextmanager
def account(limit: Any = CERTIFICATE_BUDGET, time_limit: Any = TIME_LIMIT) -> Iterator[Any]:
    """Open the account of one certificate: every charge inside goes to it (time_limit None: no clock)."""
    acc = Account(limit, time_limit)
    token = _CURRENT.set(acc)  # type: ignore[arg-type]
    try:
        yield acc
    finally:
        _CURRENT.reset(token)


def active() -> bool:
    """Is an account open?  (Callers skip working out a cost when none is.)"""
    return _CURRENT.get() is not None


def charge(cost: int, what: str) -> None:
    """Charge ``cost`` word operations to the open account; reject once it is overdrawn."""
    acc = _CURRENT.get()
    if acc is not None:
        acc.spent += cost
        if acc.spent > acc.limit:
            require_budget(False, f"over the certificate's work budget: {what} brings the certificate's estimated work "
                    f"to {acc.spent:.2e} word operations > {acc.limit:.0e}")
        acc.charges += 1
        if acc.deadline is not None and (not acc.charges & 63 or cost >= BIG_CHARGE) and process_time() > acc.deadline:
            require_budget(False, f"over the kernel's time limit: no verdict after {acc.time_limit} s of CPU time "
                                  f"({what} was next)")


def memo(key: tuple[str, Sequence[int]], compute: Callable[..., Any]) -> Any:
    """compute(), remembered in the open account under ``key``: a result shared between claims
    (a squarefree part, a proved radius) is computed and charged once per certificate."""
    acc = _CURRENT.get()
    if acc is None:
        return compute()
    if key not in acc.memo:
        acc.memo[key] = compute()
    return acc.memo[key]


def affordable(cost: int) -> bool:
    """Would ``cost`` more word operations still fit in the open account?"""
    acc = _CURRENT.get()
    return acc is None or acc.spent + cost <= acc.limit


def within_budget(cost: int, what: str, limit: int = WORK_BUDGET) -> None:
    """Reject (never run) a computation whose estimated cost exceeds ``limit`` or what is left of
    the certificate's account; otherwise charge it: a certificate must not make the kernel work
    for minutes before its verdict."""
    require_budget(cost <= limit, f"over the kernel's work budget: {what} (estimated {cost:.2e} word "
            f"operations > {limit:.0e})")
    charge(cost, what)


# ------------------------------------------------------------------ cost formulas
def words(bits: int) -> int:
    """Machine words of a bits-bit integer (at least one)."""
    return 1 + bits // 64


def sturm_cost(degree: int, bits: int) -> int:
    """degree^4 bits^2: the price of a pseudo-remainder sequence (gcd with the derivative, Sturm
    sequence) of a degree-``degree`` integer polynomial with ``bits``-bit coefficients."""
    return degree ** 4 * bits ** 2


def within_sturm_budget(degree: int, bits: int, what: str) -> None:
    """Reject, before it starts, a pseudo-remainder sequence over STURM_BUDGET or over what is left
    of the certificate's account (its steps charge their actual cost as they run)."""
    cost = sturm_cost(degree, bits)
    require_budget(cost <= STURM_BUDGET, f"over the kernel's work budget: {what} of a polynomial of degree {degree} "
            f"with {bits}-bit coefficients (degree^4 bits^2 > {STURM_BUDGET:.0e})")
    require_budget(affordable(cost // STURM_WORDS), f"over the certificate's work budget: {what} of a polynomial of "
            f"degree {degree} with {bits}-bit coefficients (estimated {cost // STURM_WORDS:.2e} word operations "
            "more than the certificate has left)")


def remainder_step_cost(length: int, lead_bits: int, other_bits: int) -> int:
    """One reduction step of a pseudo-remainder: a polynomial of ``length`` coefficients multiplied
    and reduced, its content removed (gcds, quadratic in the words)."""
    w = words(lead_bits + other_bits)
    return length * (PYTHON_OP + w * (4 + w))


def descartes_node_cost(degree: int, bits: int, end_bits: int = 0) -> int:
    """One Descartes test (a Moebius transform by Horner and a Taylor shift; polys.descartes_variations):
    about 2 (degree + 1)^2 interpreted integer operations, the degree^2 products of the Horner step each of a
    number of up to ``bits`` bits (the coefficients' plus degree times the ends') by one of ``end_bits`` bits,
    and the degree^2 / 2 additions of the Taylor shift on numbers of up to ``bits`` bits.  Calibrated by
    benchmarks/kernel_cost_model.py (a fit over degrees 10-200, coefficients of 8-2048 bits, ends of 2-200 bits:
    22 RATE-units per interpreted operation, 0.45 per word of a product, 0.55 per word of an addition); the
    former price, 2 (degree + 1)^2 (PYTHON_OP + w) + ..., charged every addition like an interpreted
    operation and ran 4 to 20 times high (issue 22)."""
    w = words(bits)
    return CALL + (degree + 1) ** 2 * (2 * PYTHON_OP + w * (2 * words(end_bits) + 1) // 4)


def content_cost(count: int, den_bits: int, other_bits: int) -> int:
    """``count`` gcds (and products, exact quotients) of integers of up to ``den_bits`` + ``other_bits`` bits:
    polys.integer_coefficients, whose coefficients share a common denominator of ``den_bits`` bits.  Quadratic in
    the words (CPython's gcd is Lehmer's; numbers sharing a large factor take its slow path: measured about 2e8
    words^2 a second on the red team's 1/d_k polynomials, so one word^2 per unit is within 2x of RATE)."""
    w = words(den_bits + other_bits)
    return count * (PYTHON_OP + w * w)


def fraction_products_cost(count: int, bits: int) -> Any:
    """``count`` Fraction products and sums of numbers of about ``bits`` bits (each normalised by gcds,
    quadratic in the words)."""
    w = words(bits)
    return count * (FRACTION_WEIGHT + 2 * w * w)


def condition_cost(terms: int, n: int, d_terms: int) -> int:
    """One generator-facet condition: g_j N_k w for ``terms`` coefficient matrices in dimension n, times
    D (``d_terms`` coefficients), made coprime (measured: 40-90 us each at degree 2)."""
    return 1000 + 2 * PYTHON_OP * terms * (n + 2 * d_terms)


def modular_squarefree_cost(degree: int, bits: int) -> int:
    """A gcd of p and p' modulo a prime: the reduction of the coefficients, then degree^2 small operations."""
    return (degree + 1) * words(bits) + 4 * (degree + 1) ** 2


def disk_step_cost(terms: Any) -> Any:
    """One step (or one step-size trial) of the Bernstein positivity proof (exactinv_check.bernstein): a few
    operations on 128-bit disks per term b_{k,m} t^(m-1) e^(-z_k t) (``terms`` of them in all); measured about
    1 ms of work per term and step at degree 15."""
    return DISK_STEP * terms


def evaluation_cost(degree: int, bits: int, end_bits: int = 0) -> int:
    """One exact value of a degree-``degree`` polynomial with ``bits``-bit coefficients at a rational of
    ``end_bits``-bit numerator and denominator (polys.sign_at, homogenised Horner from the low end): step k
    multiplies the running sum (bits + k end_bits bits) by the denominator, the coefficient by n^k (k end_bits
    bits) and n^k by n -- products by powers of the point, which the former price left out (2.5 to 4 times low
    at degree 200; issue 22) -- plus a few interpreted operations."""
    e = words(end_bits)
    grown = words(bits + degree * end_bits)
    power = words(degree * end_bits)
    return (degree + 1) * (4 * PYTHON_OP + e * (grown + power) + words(bits) * (e + power) // 2)


def sparse_read_cost(entries: int, longest_chars: int) -> int:
    """Reading ``entries`` nonzero entries of a sparse matrix (version 3), each a number string of at most
    ``longest_chars`` characters: a regular-expression match and a Fraction each (decimal-to-binary
    conversion, quadratic in the words)."""
    w = words(4 * longest_chars)
    return entries * (FRACTION_WEIGHT + 2 * w * w)


# Limits on what one certificate may ask of the kernel, each named after what it bounds (the module that
# uses it in parentheses).  A certificate beyond one is rejected, never accepted.
MAX_TIE_POLE_BITS = 4096  # (balanced_tie) bits of a pole's coordinates
MAX_BERNSTEIN_STEPS = 8000  # (bernstein) steps of the compact piece (the engine gives up after 4000)
# (bernstein) step-size trials in all (a bounded verdict: each trial is a few disk operations per pole)
MAX_BERNSTEIN_TRIALS = 40000
MAX_BERNSTEIN_DEGREE = 16  # (bernstein) the largest deg h the general proof takes
BERNSTEIN_REACH_TERMS = 24  # (bernstein) Taylor terms of f at 0 beyond its first nonzero one in the longer bound near 0
MAX_RATIONAL_BISECTIONS = 4000  # (bernstein) bisections to pin a rational pole
MAX_RATIONAL_POLE_EXPONENT = 2000  # (bernstein) the largest degree of F(u) for rational poles
# (claims_control) the gain LP's rows recomputed: dense Fraction products (about 10-30 s at most)
GAIN_WORK_BUDGET = 10 * WORK_BUDGET
# (conditions) about 20-45 s of conditions (40-90 us each, measured with degree 2, quiet and in CI)
MAX_CONDITIONS = 500_000
MAX_CONE_PAIRS = 2_000_000  # (cones) bound on the adjacency tests at one degenerate vertex
MAX_CONE_RAYS = 200_000  # (cones) bound on the rays the double description holds at once
MAX_WEIERSTRASS = 40  # (disks) refinement steps of the root approximations
MAX_DIGITS = 4000  # (format) characters of every number string: parsing is never the bottleneck
MAX_DIMENSION = 2000  # (format) every vector and matrix dimension
# (format) every polynomial the kernel builds from a certificate (an algebraic number: 201 coefficients)
MAX_DEGREE = 200
# (format) an algebraic number's polynomial (and a radius's d_j): not capped at MAX_DEGREE but priced by its size --
# its Descartes tests, signs at rationals and gcds are charged as they run (issue 22: a genuine rho of degree 272)
MAX_ALGEBRAIC_DEGREE = 1000
MAX_METHOD_DEGREE = 64  # (format) deg g and deg h of the method r = g/h after trimming
# (format) coefficient polynomials d_j of the radius the kernel computes (a longer scan cannot be certified)
MAX_COEFFICIENTS = 4096
MAX_TAIL_INDEX = 1 << 20  # (format) the largest tail index of a radius claim
MAX_POLES = 16  # (format) poles of a balanced tie (the radius claim's "poles")
MAX_LINE_EXPONENT = 64  # (format) the largest N = max |n_k| of the line-pole trigonometric polynomial (degree 2N)
HORIZON_BITS = 64  # (format) bits of the pruning horizon's (and scale's) numerator and denominator
MAX_RATIONAL_PIECES = 512  # (format) pieces of a pruning record in u = h/(s + h)
MAX_PIN = 4000  # (line_poles) bisections to pin a rational root
MAX_LP_PIECES = 200_000  # (lp_pieces) pieces over all facets: a bound before any parsing of their ends
# (lp_pieces) all pieces of one record together (measured: ~5 ms a piece in R^16-R^20)
LP_WORK_BUDGET = 50 * WORK_BUDGET
MAX_ROOT_BISECTIONS = 4000  # (polys)
MEMO_MIN_DEGREE = 32  # (validset) a polynomial's first sign change is remembered for the certificate above this degree
MAX_PACKED_BYTES = 1 << 27  # (pruning) the packed rows' table: every slot as wide as the widest row needs
MAX_SLOT_TESTS = 4 * 10**8  # (pruning) vertex-facet tests at the ends past the blocks (the 10,000-gon needs 1.3e8: 5 s)
MAX_REFINEMENTS = 20000  # (reals)
MAX_TAIL_REFINE = 2000  # (tail) bisections when separating a real pole from other roots
MAX_PRINT_BISECTIONS = 400  # (text)
MAX_TIE_DEGREE = 400  # (tie) the largest degree of T the kernel will interpolate
MAX_TIE_ISOLATE = 4000  # (tie)


# Limits on what one certificate may ask of the kernel, each named after what it bounds (the module that
# uses it in parentheses).  A certificate beyond one is rejected, never accepted.
# (line_algebraic) the largest deg f (in y) and deg m handled here: the kernel's bound on deg h (bernstein)
MAX_LINE_DEGREE = 16
