"""Systematics of four-link band mechanisms (Ebert (2015), ch. 2.5.2, Bild
2.6-2.8): every structure that the text's construction rules derive, as a
runnable model (one class per structure, built by
:class:`acausal2d.library.belt.systematics.BandStructure` from its code).

The classes are generated: :func:`acausal2d.library.belt.structures.derive_structures`
derives the structures from the rules (chain, bands, discs, frame, the two
readings of a structure identified), and this module makes one model class
per derived structure, built in the reading :data:`DESCRIPTIONS` names (the
one its skeleton assembles in; the name of Ebert (2015) where it has one, DB~DS)
with that entry's description; a structure the rules gave without an entry
would be built in its canonical reading.

How the structures are enumerated (the figures are lost; the rules are
those of the text): a band replaces a rigid link of a
four-link chain whose two joints are revolute (R1, R3: "a combination of
rolling joint and prismatic joint is not possible", so the band's joints
are never S); each band end is a pin D or a band joint B on a disc of the
neighbouring link, at least one B (R2: D-B or B-B); two bands are never
adjacent (the joint between them would join no rigid link).  The starting
chains are the four-bar DDDD, the slider-crank DDDS and the cross-slider
DDSS (R5, R6); the slotted-slider chain DSDS has an S at every link and
yields nothing (R3).  Each chain gives one structure per choice of the
frame (cyclic change of the reference link, R5), read from the frame
(first and last letter: the joints on the frame), mirror readings being
the same structure (DB~DD = DD~BD).  This gives

========================  ==========================================
chain                     structures
========================  ==========================================
4-bar, band D-B           DB~DD, D~BDD, B~DDD, (band frame) BDDD
4-bar, band B-B           DB~BD, B~BDD, (band frame) BDDB
4-bar, 2 bands D-B (a)    D~BD~B, (band frame) DB~DB
4-bar, 2 bands D-B (b)    B~DD~B, D~BB~D, (band frame) DD~BB
4-bar, 2 bands B-B, D-B   B~BD~B, D~BB~B, (band frame) BB~DB,
                          (band frame) DB~BB
4-bar, 2 bands B-B, B-B   B~BB~B, (band frame) BB~BB
slider-crank, band B-D    SB~DD, D~BSD, SDD~B, (band frame) DDSB
slider-crank, band D-B    DB~DS, SDB~D, DSD~B, (band frame) DSDB
slider-crank, band B-B    SB~BD, SDB~B, DSB~B, (band frame) BDSB
cross-slider, band D-B    SB~DS, SSB~D, SSD~B, (band frame) DSSB
cross-slider, band B-B    SB~BS, SSB~B, (band frame) BSSB
========================  ==========================================

((a): each rigid link carries a pivot and a disc; (b): one rigid link
carries two discs, the other two pivots), i.e. 18 four-bar structures from
6 chains and 19 slider structures from 5 chains, against Ebert's (2015) 16
from 5 starting combinations (Bild 2.6) and 27 from 7 (Bild 2.7, 2.8). The
stated rules do not reproduce those counts: dropping one of the two-
structure four-bar chains gives 16, and the slider counts presumably
include the grey form-change variants of slotted mechanisms ([Vol92]),
which the text does not define. The text itself calls two-band structures
and the band as the frame rare in practice.

Modelled here: the 19 structures with one band that is a moving link (the
table's entries without "(band frame)" and with one band, list
``MODELS``), the 7 one-band structures with the band as the frame
(``BAND_FRAME``, code with a trailing ``~``: the band is a taut straight
line y = 0 in the ground on which the discs roll without slip; classes
named ``<code>_frame``; in BSSB the coupler slides on the guide of the
first rolling link and is driven relative to that guide), the 6 two-band
structures with the bands L1 and L3 (``TWO_BANDS``, built by
:class:`acausal2d.library.belt.systematics_two.TwoBandStructure`: the
coupler hangs on the two bands like a swing, its angle driven, a vertical
load) and the 5 two-band structures with the band L2 and the band as the
frame (``TWO_BANDS_FRAME``, classes ``<code>_frame``: a crank pivoted on
the band frame, driven clockwise, or for BB~DB~ and BB~BB~, where both
frame-side links are wheels rolling on the band, a winch disc at J2 driven
relative to its wheel; a wheel rolling on the band frame loaded by a
torque): all 37.  Driven counterclockwise, DB~DB~ reaches a dead position
within 0.04 s (the band's line through the wheel's contact point, its
instantaneous centre; this was the earlier integration failure).

Every model: joints at the corners of the skeleton quadrilateral J1 =
(0, 0), J2 = (0.05, 0.15), J3 = (0.3, 0.22), J4 = (0.35, 0) m, discs of
radius 0.03 m, massless links; the first link of the frame's branches is
driven (0.5 rad/s or 0.02 m/s), the link carrying the band's other end is
loaded so that the band pulls with 10 N at t = 0.  Class names spell the
code with ``_`` for ``~`` (DB_DD is DB~DD); each class docstring says what
the structure is.  ``acausal2d simulate models/band_systematics.py --model
DB_DD`` runs one.
"""
from acausal2d.library.belt.structures import derive_structures
from acausal2d.library.belt.systematics import BandStructure
from acausal2d.library.belt.systematics_two import TwoBandStructure

DESCRIPTIONS = {
    "DB~DD":
     "DB~DD (4-bar, band D-B): cam disc on a crank pivoted in the frame, band to the tip of a "
     "rocker pivoted in the frame.",
    "D~BDD":
     "D~BDD (4-bar, band D-B): band from a frame pin to a disc on the coupler, which is pinned "
     "to a rocker.",
    "B~DDD":
     "B~DDD (4-bar, band D-B): band from a disc fixed in the frame to a pin on the coupler, "
     "which is pinned to a rocker.",
    "DB~BD":
     "DB~BD (4-bar, band B-B): band between discs on two cranks pivoted in the frame.",
    "B~BDD":
     "B~BDD (4-bar, band B-B): band from a disc fixed in the frame to a disc on the coupler, "
     "which is pinned to a rocker.",
    "SB~DD":
     "SB~DD (slider-crank, band B-D): disc on a slider guided in the frame, band to the tip of "
     "a rocker.",
    "D~BSD":
     "D~BSD (slider-crank, band B-D): band from a frame pin to a disc on a slider guided on a "
     "rocker.",
    "SDD~B":
     "SDD~B (slider-crank, band B-D): slider in the frame, coupler pinned to it, band from the "
     "coupler's pin to a disc fixed in the frame.",
    "DB~DS":
     "DB~DS (slider-crank, band D-B): disc on a crank, band to a slider guided in the frame "
     "(Ebert (2015), ch. 7.2.2, 'mit Schieber im Gestell').",
    "SDB~D":
     "SDB~D (slider-crank, band D-B): slider in the frame, a link pinned to it carries a disc, "
     "band to a frame pin.",
    "DSD~B":
     "DSD~B (slider-crank, band D-B): crank with a guide, the slider's pin holds the band from "
     "a disc fixed in the frame.",
    "SB~BD":
     "SB~BD (slider-crank, band B-B): disc on a slider guided in the frame, band to a disc on "
     "a rocker.",
    "SDB~B":
     "SDB~B (slider-crank, band B-B): slider in the frame, a link pinned to it carries a disc, "
     "band to a disc fixed in the frame.",
    "DSB~B":
     "DSB~B (slider-crank, band B-B): crank with a guide, disc on its slider, band to a disc "
     "fixed in the frame.",
    "SB~DS":
     "SB~DS (cross-slider, band D-B): disc on a slider guided in the frame, band to a second "
     "slider guided in the frame.",
    "SSB~D":
     "SSB~D (cross-slider, band D-B): slider in the frame carries the guide of a second slider "
     "with a disc, band to a frame pin.",
    "SSD~B":
     "SSD~B (cross-slider, band D-B): slider in the frame carries the guide of a second "
     "slider, band from its pin to a disc fixed in the frame.",
    "SB~BS":
     "SB~BS (cross-slider, band B-B): discs on two sliders guided in the frame, band between "
     "them.",
    "SSB~B":
     "SSB~B (cross-slider, band B-B): slider in the frame carries the guide of a second slider "
     "with a disc, band to a disc fixed in the frame.",
    "BDDD~":
     "BDDD~, the band as the frame (4-bar, band D-B): a rocker pivoted on the band drives a "
     "coupler whose other link carries a disc rolling on the band.",
    "BDDB~":
     "BDDB~, the band as the frame (4-bar, band B-B): a disc rolling on the band, its link "
     "pinned to a driven coupler, whose other link carries a second disc rolling on the band.",
    "DDSB~":
     "DDSB~, the band as the frame (slider-crank, band B-D): a crank pivoted on the band, a "
     "coupler carrying a guide, the slider on it carries a disc rolling on the band.",
    "DSDB~":
     "DSDB~, the band as the frame (slider-crank, band D-B): a crank pivoted on the band with "
     "a guide, its slider's pin carries a link with a disc rolling on the band.",
    "BDSB~":
     "BDSB~, the band as the frame (slider-crank, band B-B): a disc rolling on the band, its "
     "link pinned to a driven coupler carrying a guide, whose slider carries a second rolling "
     "disc.",
    "DSSB~":
     "DSSB~, the band as the frame (cross-slider, band D-B): a crank pivoted on the band with "
     "a guide, a slider on it with a second guide, whose slider carries a disc rolling on the "
     "band.",
    "BSSB~":
     "BSSB~, the band as the frame (cross-slider, band B-B): a disc rolling on the band "
     "carries a guide, the coupler slides on it (driven relative to the guide) and carries the "
     "guide of a slider with a second rolling disc.",
    "D~BD~B":
     "D~BD~B (4-bar, 2 bands D-B (a)): a frame pin and a frame disc hold the bands on which "
     "the coupler (a disc and a pin) hangs.",
    "B~DD~B":
     "B~DD~B (4-bar, 2 bands D-B (b)): two frame discs hold the bands that hang the coupler by "
     "two pins.",
    "D~BB~D":
     "D~BB~D (4-bar, 2 bands D-B (b)): two frame pins hold the bands that wrap two discs on "
     "the coupler.",
    "B~BD~B":
     "B~BD~B (4-bar, 2 bands B-B, D-B): a B-B band from a frame disc to a coupler disc, a D-B "
     "band from the coupler's pin to a frame disc.",
    "D~BB~B":
     "D~BB~B (4-bar, 2 bands B-B, D-B): a D-B band from a frame pin to a coupler disc, a B-B "
     "band from a second coupler disc to a frame disc.",
    "B~BB~B":
     "B~BB~B (4-bar, 2 bands B-B, B-B): two B-B bands between frame discs and coupler discs.",
    "DB~DB~":
     "DB~DB~, the band as the frame with a second band L2 (4-bar, 2 bands D-B (a)): a crank "
     "pivoted on the band frame carries a disc, the band L2 runs to a pin on a wheel rolling "
     "on the band frame.",
    "DD~BB~":
     "DD~BB~, the band as the frame with a second band L2 (4-bar, 2 bands D-B (b)): the band "
     "L2 from the tip of a crank pivoted on the band frame to a disc on a wheel rolling on it.",
    "DB~BB~":
     "DB~BB~, the band as the frame with a second band L2 (4-bar, 2 bands B-B, D-B): the band "
     "L2 from a disc on a crank pivoted on the band frame to a disc on a wheel rolling on it.",
    "BB~DB~":
     "BB~DB~, the band as the frame with a second band L2 (4-bar, 2 bands B-B, D-B): two "
     "wheels rolling on the band frame, the band L2 from a winch disc on the first (driven) to "
     "a pin on the second.",
    "BB~BB~":
     "BB~BB~, the band as the frame with a second band L2 (4-bar, 2 bands B-B, B-B): two "
     "wheels rolling on the band frame, the band L2 from a winch disc on the first (driven) to "
     "a disc on the second.",
}
"""The reading each structure is built in, and what the structure is."""


def _reading(structure):
    """The reading of ``structure`` named in :data:`DESCRIPTIONS`, else its
    canonical code."""
    named = [r for r in structure.readings if r in DESCRIPTIONS]
    return named[0] if named else structure.code


def _class_name(code):
    """``DB~DD`` -> ``DB_DD``; a band as the frame (trailing ``~``) ->
    ``BDDD_frame``."""
    return code.replace("~", "_") + ("frame" if code.endswith("~") else "")


def _model_class(structure):
    """The model class of one derived structure."""
    code = _reading(structure)
    base = TwoBandStructure if structure.bands == 2 else BandStructure
    doc = DESCRIPTIONS.get(code, "%s (%s, %d band(s)): derived from the rules."
                           % (code, structure.chain, structure.bands))
    return type(_class_name(code), (base,), {"code": code, "__doc__": doc,
                                             "__module__": __name__,
                                             "__qualname__": _class_name(code)})


STRUCTURES = derive_structures()
"""The derived structures (:class:`~acausal2d.library.belt.structures.Structure`)."""
CLASSES = [_model_class(s) for s in STRUCTURES]
"""One model class per derived structure, in the order of :data:`STRUCTURES`."""
globals().update({cls.__name__: cls for cls in CLASSES})

MODELS = [c for c in CLASSES if c.code.count("~") == 1 and not c.code.endswith("~")]
"""The 19 structures with one band that is a moving link."""
BAND_FRAME = [c for c in CLASSES if c.code.count("~") == 1 and c.code.endswith("~")]
"""The 7 one-band structures with the band as the frame."""
TWO_BANDS = [c for c in CLASSES if c.code.count("~") == 2 and not c.code.endswith("~")]
"""The 6 two-band structures with the bands L1 and L3."""
TWO_BANDS_FRAME = [c for c in CLASSES if c.code.count("~") == 2 and c.code.endswith("~")]
"""The 5 two-band structures with the band L2 and the band as the frame."""
