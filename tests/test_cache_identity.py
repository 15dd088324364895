"""The check of a cached library at load (issue: the output path at the
floor): the SHA-256 is computed where the file's size, modification time,
inode or mode differ from those recorded at publish, and always by
``acausal2d cache verify``; a library as published is not read again."""
import os

import pytest

from acausal2d.cli import main
from acausal2d.runtime import cstore


@pytest.fixture
def published(tmp_path, monkeypatch):
    """A library published into a cache folder of its own, and a counter
    of the SHA-256 computations."""
    monkeypatch.setenv(cstore.CACHE_ENV, str(tmp_path / "cache"))
    folder = cstore.folder()
    built = os.path.join(folder, "built.so")
    with open(built, "wb") as fh:
        fh.write(os.urandom(4096))
    target = os.path.join(folder, "a2d_model-0123.so")
    cstore.publish(built, target)
    counted = []
    real = cstore.file_digest
    monkeypatch.setattr(cstore, "file_digest", lambda p: counted.append(p) or real(p))
    return target, counted


def test_a_library_as_published_is_not_hashed_at_load(published):
    target, counted = published
    assert cstore.verified(target) and cstore.verified(target)
    assert counted == []


def test_a_changed_identity_costs_one_full_check(published):
    target, counted = published
    st = os.stat(target)
    os.utime(target, ns=(st.st_atime_ns, st.st_mtime_ns + 1000))    # touched, bytes the same
    assert cstore.verified(target) and counted == [target]
    assert cstore.verified(target) and counted == [target]          # the new identity recorded


def test_changed_bytes_with_the_old_time_are_found_by_cache_verify(published, capsys):
    target, counted = published
    st = os.stat(target)
    with open(target, "r+b") as fh:                                 # one bit, size kept
        byte = fh.read(1)[0]
        fh.seek(0)
        fh.write(bytes([byte ^ 1]))
    os.utime(target, ns=(st.st_atime_ns, st.st_mtime_ns))           # and its time put back
    assert main(["cache", "verify"]) == 0
    out, err = capsys.readouterr()
    assert "1 file checked" in out and os.path.basename(target) in out
    assert "is damaged" in err and not os.path.exists(target)


def test_a_truncated_library_is_found_at_load(published):
    target, counted = published
    with open(target, "r+b") as fh:
        fh.truncate(100)
    assert not cstore.verified(target) and not os.path.exists(target)
