"""Hand-offs run one way (issue 34): a runtime helper returns what it
decided and the simulation applies it; nothing outside
``runtime/simulation.py`` assigns to a simulation's attributes, mutates its
lists or calls its private methods."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
WRITES = re.compile(r"\b(?:self\.)?sim\.(?:\w+\s*(?:=(?!=)|\+=)|\w+\.(?:append|extend|clear|pop)\(|_\w+\()")


def test_nothing_writes_into_a_simulation_from_outside():
    offenders = []
    for path in sorted((ROOT / "acausal2d").rglob("*.py")):
        if "library" in path.parts or path.name == "simulation.py":
            continue
        for k, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if WRITES.search(line):
                offenders.append("%s:%d: %s" % (path.relative_to(ROOT), k, line.strip()))
    assert offenders == []


def test_the_pattern_catches_the_old_writes():
    for line in ("sim.t = last[0]", "self.sim.stopped = (", "sim.out.append((t, z))",
                 "sim.singular.extend(x)", "self.form, self.prob, self.solver, _ = sim._solver()"):
        assert WRITES.search(line), line
    for line in ("t = sim.t", "if sim.t == 0:", "sim.ev.residual(t, z, sim.d)"):
        assert not WRITES.search(line), line
