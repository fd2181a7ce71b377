"""The exceptions exactinv raises (the bottom layer: imports nothing from exactinv).

Following python-flint's three outcomes of a verifier, a claim is *proved*
(a result is returned), *refuted with a witness* (a result with
``holds == False`` and a witness), or *undecided* (:class:`Undecided` is
raised) -- never silently guessed.

Every exception derives from :class:`ExactinvException`.  Errors about the
*input* derive from :class:`ExactinvError`, which is also a :class:`ValueError`
(callers may catch either, as with hypothesis' ``InvalidArgument``).  An
engine bug (:class:`VerificationFailed`, a :class:`RuntimeError`) and a
question the engine cannot decide (:class:`Undecided`) are *not*
``ValueError``s, so catching bad input never hides them.

>>> issubclass(InvalidInput, ValueError), issubclass(VerificationFailed, ValueError)
(True, False)
"""

from __future__ import annotations

__all__ = [
    "ExactinvException",
    "ExactinvError",
    "InvalidInput",
    "EmptyPolyhedron",
    "NotInvariant",
    "VerificationFailed",
    "Undecided",
]


class ExactinvException(Exception):
    """Base class of every exception exactinv raises."""


class ExactinvError(ExactinvException, ValueError):
    """Base class of every error about the input (a :class:`ValueError`)."""


class InvalidInput(ExactinvError):
    """An argument is malformed: wrong type, shape, a float without opt-in,
    NaN, a ragged matrix, sigma_0 != 1, ...  The message names the argument,
    the position and what is wrong."""


class EmptyPolyhedron(InvalidInput):
    """The polyhedron {x : Gx <= b} has no point, so invariance questions about
    it are vacuous; exactinv reports this instead of solving an LP over it."""


class NotInvariant(ExactinvError):
    """A computation needs an invariant polyhedron (e.g. a threshold of a
    discretization method) but P is not invariant for x' = Ax.  The
    exception's ``witness`` attribute holds the exact witness."""

    def __init__(self, message: str, witness=None):
        super().__init__(message)
        self.witness = witness


class VerificationFailed(ExactinvException, RuntimeError):
    """An exact re-verification of a certificate failed.  Raised when an
    internal consistency check fails (a bug in the untrusted engine, never a
    property of the input); the checker reports such failures as verdicts."""


class Undecided(ExactinvException):
    """exactinv could neither prove nor refute the claim (for example a
    certificate that the exact fallback could not repair)."""
