"""The structures of four-link band mechanisms derived from the rules of
Ebert (2015), ch. 2.5.2 (Bild 2.6-2.8; the figures are lost, the rules are
the text's):

1. the starting chains are the four-link chains with revolute joints D and
   at most two prismatic joints S: the four-bar DDDD, the slider-crank DDDS,
   the cross-slider DDSS and the slotted slider DSDS (a chain with three
   or four S has no rotating link);
2. a band replaces a rigid link whose two joints are revolute ("a
   combination of rolling joint and prismatic joint is not possible": no S
   at a band's end);
3. each end of a band is a pin D or a band joint B on a disc of the
   neighbouring link, at least one B per band (D-B or B-B);
4. two bands are never adjacent (the joint between them would join no
   rigid link);
5. any link may be the frame (the cyclic change of the reference link), a
   band included ("the band as the frame");
6. a structure is read from the frame: its code lists the joints J1..J4
   (J4-J1 the frame link, so the first and the last letter are the joints
   on the frame) and marks a band link J_k-J_k+1 with ``~`` after J_k (a
   trailing ``~``: the frame is a band); reading the other way round is
   the same structure (``DB~DD`` = ``DD~BD``).

:func:`derive_structures` builds the structures in that order -- chain,
bands, discs, frame -- and identifies the readings of one structure.  The
rules give 37 structures: 18 from the four-bar (6 chains with bands), 12
from the slider-crank (3) and 7 from the cross-slider (2); the slotted
slider gives none (each of its links has an S).  Ebert (2015) counts 16
four-bar structures from 5 starting combinations (Bild 2.6) and 27 slider
structures from 7 (Bild 2.7, 2.8).  The stated rules do not reproduce
those counts: dropping one of the four-bar combinations that yield two
structures gives 16, and the slider counts presumably include the grey
form-change variants of slotted mechanisms, which the text does not
define.  The text itself calls two-band structures and the band as the
frame rare in practice.
"""
from collections import namedtuple
from itertools import product

__all__ = ["Structure", "derive_structures", "derived_chains", "readings", "code_of",
           "CHAIN_NAMES"]

CHAIN_NAMES = {"DDDD": "4-bar", "DDDS": "slider-crank", "DDSS": "cross-slider",
               "DSDS": "slotted slider"}
"""The starting chains (canonical joint cycle) and their names."""

Structure = namedtuple("Structure", "code chain bands readings")
Structure.__doc__ = """One derived structure: ``code`` its canonical reading
(the smaller of the two readings, see :func:`readings`), ``chain`` the
starting chain's name, ``bands`` the number of bands, ``readings`` both
codes of the structure (read from the frame one way and the other)."""


def _rotations(word):
    return [word[k:] + word[:k] for k in range(len(word))]


def _cycle_class(word):
    """Canonical form of a cyclic word under rotation and reflection."""
    return min(_rotations(word) + _rotations(word[::-1]))


def code_of(joints, bands):
    """The code of the joints J1..J4 (letters) and the band links (set of
    k in 1..4, link J_k-J_k+1; 4 = the frame J4-J1)."""
    return "".join(j + ("~" if k + 1 in bands else "") for k, j in enumerate(joints))


def readings(joints, bands):
    """Both codes of a structure: read from the frame J1 -> J4 and J4 -> J1
    (the reversed reading has the joints in reverse order, link k becoming
    link 4 - k, the frame staying link 4)."""
    back = {4 if k == 4 else 4 - k for k in bands}
    return code_of(joints, bands), code_of(joints[::-1], back)


def _chains():
    """The starting chains (rule 1): joint cycles of D and at most two S,
    one per class under rotation and reflection."""
    return sorted({_cycle_class("".join(w)) for w in product("DS", repeat=4)
                   if w.count("S") <= 2})


def _band_sets(chain):
    """Sets of band links of ``chain`` (link k joins joints k and k+1, mod
    4): no two adjacent (rule 4), no S at a band's end (rule 2)."""
    out = []
    for n in (1, 2):
        for links in product(range(4), repeat=n):
            if list(links) != sorted(set(links)):
                continue
            if n == 2 and (links[1] - links[0]) % 4 in (1, 3):
                continue
            if any("S" in (chain[k], chain[(k + 1) % 4]) for k in links):
                continue
            out.append(set(links))
    return out


def _disc_choices(chain, links):
    """Joint words with each band end a pin D or a disc B, at least one B
    per band (rule 3)."""
    ends = sorted({j for k in links for j in (k, (k + 1) % 4)})
    for letters in product("DB", repeat=len(ends)):
        word = list(chain)
        for j, ch in zip(ends, letters):
            word[j] = ch
        if all("B" in (word[k], word[(k + 1) % 4]) for k in links):
            yield "".join(word)


def derive_structures():
    """The structures the rules derive (module docstring), in the order
    chain, bands, discs, frame, as a list of :class:`Structure` (the chains
    with bands they come from: :func:`derived_chains`)."""
    seen, out = set(), []
    for chain in _chains():
        for links in _band_sets(chain):
            for word in _disc_choices(chain, links):
                for frame in range(4):          # rule 5: link `frame` is the frame
                    joints = word[frame + 1:] + word[:frame + 1]
                    bands = {(k - frame - 1) % 4 + 1 for k in links}
                    pair = readings(joints, bands)
                    if min(pair) in seen:
                        continue
                    seen.add(min(pair))
                    out.append(Structure(min(pair), CHAIN_NAMES[chain], len(links),
                                         tuple(sorted(set(pair)))))
    return out


def derived_chains():
    """The chains with bands (starting chain, band links and discs, before a
    frame is chosen), one per class under rotation and reflection: a dict
    {starting chain name: number of chains with bands}."""
    counts = {}
    for chain in _chains():
        classes = set()
        for links in _band_sets(chain):
            for word in _disc_choices(chain, links):
                marked = [word[k] + ("~" if k in links else "") for k in range(4)]
                classes.add(_marked_class(marked))
        counts[CHAIN_NAMES[chain]] = len(classes)
    return counts


def _marked_class(marked):
    """Canonical form of a cycle of joints with band marks (``"B~"``: a band
    follows this joint) under rotation and reflection."""
    forms = []
    for k in range(4):
        rot = marked[k:] + marked[:k]
        forms.append("".join(rot))
        joints = [m[0] for m in rot][::-1]
        bands = [m.endswith("~") for m in rot]
        back = [bands[(4 - 2 - i) % 4] for i in range(4)]     # link i of the reverse
        forms.append("".join(j + ("~" if b else "") for j, b in zip(joints, back)))
    return min(forms)
