"""docs/coverage.md, the coverage table of the two seeds: every row once,
the counts as the rows say, every file, class and test named in an
implemented row present, and no absent row without its reason."""
import re
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TABLE = ROOT / "docs" / "coverage.md"
STATUSES = ("I", "P", "A", "n/a")


def rows():
    out = {}
    for line in TABLE.read_text().splitlines():
        m = re.match(r"\| ([DT]\d+[a-f]?) \| (.*?) \| (I|P|A|n/a) \| (.*) \|$", line)
        if m:
            assert m.group(1) not in out, "row %s twice" % m.group(1)
            out[m.group(1)] = {"item": m.group(2), "status": m.group(3), "where": m.group(4)}
    return out


def test_every_row_of_the_seed_table_is_there_once():
    expected = {"D%d" % k for k in range(1, 78)} | {"D27" + c for c in "abcdef"} | \
        {"D10a", "D10b", "D62a"} | {"T%d" % k for k in range(1, 30)}
    assert set(rows()) == expected


def test_counts_match_the_rows():
    r = rows()
    counted = {k: v["status"] for k, v in r.items() if v["status"] != "n/a"}
    text = TABLE.read_text()
    for seed, label in (("D", "dissertation (D)"), ("T", "talk (T)")):
        c = Counter(s for k, s in counted.items() if k[0] == seed)
        m = re.search(r"\| %s \| (\d+) \| (\d+) \| (\d+) \| (\d+) \|" % re.escape(label), text)
        assert m, label
        assert [int(g) for g in m.groups()] == [c["I"], c["P"], c["A"], sum(c.values())], label


def test_absent_rows_say_why_they_cannot_be_built():
    for key, row in rows().items():
        if row["status"] == "A":
            reason = row["where"].lower()
            assert re.search(r"no (data|dimensions)|references only|only|neither|future work",
                             reason) and len(reason.split()) >= 8, key


def _named_files(where):
    """(path, names) of every ``path.py:Name, Name`` / ``path.py::test`` in
    the text."""
    for m in re.finditer(r"((?:[\w.]+/)+[\w.]+\.(?:py|js))(?:(::?)([\w.]+(?:, [A-Z_]\w*)*))?",
                         where):
        names = [n.split(".")[0] for n in (m.group(3) or "").split(", ") if n]
        yield m.group(1), names


def test_files_classes_and_tests_of_implemented_rows_exist():
    missing = []
    for key, row in rows().items():
        if row["status"] not in ("I", "P"):
            continue
        for path, names in _named_files(row["where"]):
            f = ROOT / path
            if not f.exists():
                missing.append("%s: %s" % (key, path))
                continue
            text = f.read_text()
            for name in names:
                if not re.search(r"(class|def) %s\b|^%s = " % (name, name), text, re.M):
                    missing.append("%s: %s in %s" % (key, name, path))
    assert not missing, missing
