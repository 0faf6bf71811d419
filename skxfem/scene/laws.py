"""The interface laws, once: each one's name and what it imposes, read everywhere else;
and the names of the multiplier spaces.

A law says what holds on Γ.  The *ties* (``bonded``, ``bilateral``) are linear:
the solver of :mod:`skxfem.solver` imposes them with multipliers on the jump
(the vector jump, or its normal part: their ``coupling``).  ``free`` imposes
nothing: traction-free faces (a crack's), no multiplier (its coupling ``"none"``).
The *contact* laws are unilateral (Signorini's conditions on the normal, with no friction,
Coulomb's or no slip): :mod:`skxfem.contact` solves them by Newton's method, and
within a load history a state may also switch an interface to a tie.

>>> [law.name for law in LAWS.values() if law.tie]
['bonded', 'bilateral', 'free']
>>> LAWS["coulomb"].unilateral, LAWS["coulomb"].tangential
(True, 'coulomb')
>>> FRICTION_LAWS                 # the laws that take Coulomb's μ (``friction``)
('coulomb',)
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["LawKind", "LAWS", "TIE_LAWS", "CONTACT_LAWS", "ALL_LAWS",
           "FRICTION_LAWS", "COUPLING", "SPACES", "in_words"]


def in_words(laws) -> str:
    """The laws of a scene's interfaces as a message quotes them: the one law, or the
    list of them (the one place a message's wording depends on their count).

    >>> in_words(["bonded"]), in_words(["bonded", "coulomb"])
    ("'bonded'", "['bonded', 'coulomb']")
    """
    laws = list(laws)
    return repr(laws[0]) if len(laws) == 1 else repr(laws)


@dataclass(frozen=True)
class LawKind:
    """What a law imposes at a point of Γ.

    ``tie``: imposed by the tie solver (else by the contact solver).
    ``unilateral``: Signorini on the normal (eq. 5), else the normal jump is
    tied (d_n = 0, λ of either sign).  ``tangential``: ``"free"`` (r_τ = 0),
    ``"stick"`` (no slip, or no slip increment where closed) or ``"coulomb"``
    (eq. 8).  ``coupling``: the jump a tie's multipliers act on, ``"bonded"``
    (the vector [[u]]) or ``"bilateral"`` (its normal part), ``"none"`` for a law
    without multipliers (``free``); the contact laws' normal multipliers are those
    of the bilateral tie.
    """

    name: str
    tie: bool
    unilateral: bool
    tangential: str
    coupling: str

    @property
    def takes_friction(self) -> bool:
        """Whether the law takes Coulomb's μ (a scene's ``friction``): Coulomb's
        tangential law only; every other law has none to give."""
        return self.tangential == "coulomb"


LAWS = {law.name: law for law in (
    LawKind("bonded", tie=True, unilateral=False, tangential="stick", coupling="bonded"),
    LawKind("bilateral", tie=True, unilateral=False, tangential="free", coupling="bilateral"),
    LawKind("free", tie=True, unilateral=False, tangential="free", coupling="none"),
    LawKind("frictionless", tie=False, unilateral=True, tangential="free",
            coupling="bilateral"),
    LawKind("coulomb", tie=False, unilateral=True, tangential="coulomb", coupling="bilateral"),
    LawKind("adhesive", tie=False, unilateral=True, tangential="stick", coupling="bilateral"),
)}
"""Every law, by name: the one table."""

TIE_LAWS = tuple(name for name, law in LAWS.items() if law.tie)
CONTACT_LAWS = tuple(name for name, law in LAWS.items() if not law.tie)
ALL_LAWS = tuple(LAWS)
FRICTION_LAWS = tuple(name for name, law in LAWS.items() if law.takes_friction)
"""The laws that need ``friction`` (Coulomb's μ) and the only ones that take it."""
COUPLING = {name: LAWS[name].coupling for name in TIE_LAWS}
"""For each tie law, the coupling its multipliers are built on."""

SPACES = ("naive", "winner", "vital")
"""The multiplier spaces a scene may choose (paper §4.2 and §5): one multiplier per cut
edge, algo1 (winner nodes), algo2 (vital edges: the default)."""
