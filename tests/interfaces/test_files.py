"""Nothing a user gives is ever overwritten (issue 21, item 2), tried on real files.

Every case below gives `exactinv certify -o` or `exactinv batch -o/--cert-dir`
an output that *is* an input -- the same path, ``./x`` for ``x``, a path
through a symbolic link to the directory, a symbolic link, a hard link, a
problem file a CSV row names -- or an existing file exactinv did not write.
Each is refused with exit 2 before any work (nothing on stdout, no Dask
cluster started), and every file of the case is unchanged afterwards, byte
for byte and in its modification time.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest

from exactinv.cli import main
from exactinv.interfaces.files import atomic_write, is_certificate, same_file

ROOT = Path(__file__).parents[2]
BOX = (ROOT / "examples" / "paper_box_taylor4.json").read_text()
DECAY = json.dumps({"name": "decay", "system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]},
                    "method": {"taylor": 1}})
OLD = 1_000_000_000  # a modification time in 2001: any write would move it


def _snapshot(root: Path) -> dict[str, tuple[bytes, int, int]]:
    """Every file below ``root``: (bytes, mtime in ns, inode); links not followed."""
    out = {}
    for p in sorted(root.rglob("*")):
        if p.is_file() and not p.is_symlink():
            st = p.stat()
            out[str(p.relative_to(root))] = (p.read_bytes(), st.st_mtime_ns, st.st_ino)
    return out


def _age(root: Path) -> None:
    for p in root.rglob("*"):
        if p.is_file() and not p.is_symlink():
            os.utime(p, (OLD, OLD))


@pytest.fixture
def corpus(tmp_path, monkeypatch):
    """A directory of real inputs: two problems, a JSON-lines file, an oracle CSV naming a problem,
    a symbolic link and a hard link to a problem, and a symbolic link to the directory itself."""
    d = tmp_path / "corpus"
    d.mkdir()
    (d / "q0.json").write_text(DECAY)
    (d / "box.json").write_text(BOX)
    (tmp_path / "lines.jsonl").write_text(DECAY + "\n")
    (tmp_path / "named.json").write_text(DECAY.replace('"decay"', '"named"'))
    (tmp_path / "rows.csv").write_text("problem,quantity,method,claimed\nnamed.json,gamma,,0.5\n")
    (tmp_path / "notes.txt").write_text("my notes, not a certificate\n")
    os.symlink(d / "q0.json", tmp_path / "soft.json")
    os.link(d / "q0.json", tmp_path / "hard.json")
    os.symlink(d, tmp_path / "dirlink")
    (d / "segment.ine").write_text("H-representation\nbegin\n2 2 integer\n1 -1\n1 1\nend\n")
    (d / "on_cdd.json").write_text(json.dumps({"system": {"A": [[-1]]}, "polyhedron": {"cdd": "segment.ine"},
                                               "method": {"taylor": 1}}))
    _age(tmp_path)
    monkeypatch.chdir(tmp_path)
    return tmp_path


CERTIFY_CASES = {
    "the same path": ["corpus/q0.json", "-o", "corpus/q0.json"],
    "./x for x": ["corpus/q0.json", "-o", "./corpus/./q0.json"],
    "an absolute path for a relative one": ["corpus/q0.json", "-o", "{root}/corpus/q0.json"],
    "through a symbolic link to the folder": ["corpus/q0.json", "-o", "dirlink/q0.json"],
    "a symbolic link to the input": ["corpus/q0.json", "-o", "soft.json"],
    "a hard link to the input": ["corpus/q0.json", "-o", "hard.json"],
    "the input given through a link": ["soft.json", "-o", "corpus/q0.json"],
    "another problem file (not a certificate)": ["corpus/q0.json", "-o", "corpus/box.json"],
    "a text file (not a certificate)": ["corpus/q0.json", "-o", "notes.txt"],
    "the cdd file the problem reads": ["corpus/on_cdd.json", "-o", "corpus/segment.ine"],
}


@pytest.mark.parametrize("case", sorted(CERTIFY_CASES))
def test_certify_never_overwrites_an_input(corpus, capsys, case):
    args = [a.replace("{root}", str(corpus)) for a in CERTIFY_CASES[case]]
    before = _snapshot(corpus)
    for extra in ([], ["--json"], ["--no-check", "--quiet"]):
        assert main(["certify", *args, *extra]) == 2, case
        out, err = capsys.readouterr()
        assert out == "", "the computation ran before the output was refused"
        assert err.startswith("exactinv: -o ") and len(err.strip().splitlines()) == 1, err
        assert "never overwrites" in err or "not an exactinv certificate" in err, err
    assert _snapshot(corpus) == before, case


def test_certify_replaces_its_own_certificate_atomically(corpus, capsys):
    out = corpus / "cert.json"
    assert main(["certify", "corpus/q0.json", "-o", str(out), "--quiet"]) == 0
    first = out.read_bytes()
    assert is_certificate(str(out)) and capsys.readouterr().out == ""
    assert main(["certify", "corpus/q0.json", "--method", "heun", "-o", str(out), "--quiet"]) == 0
    assert out.read_bytes() != first and is_certificate(str(out))  # a certificate is replaced by a certificate
    assert sorted(p.name for p in corpus.iterdir() if p.name.startswith(".")) == []  # no temporary file left
    assert main(["check", str(out)]) == 0


BATCH_CASES = {
    "-o an input problem inside a scanned folder": ["corpus", "-o", "corpus/q0.json"],
    "-o ./x of an input inside a scanned folder": ["corpus", "-o", "./corpus/q0.json"],
    "-o a problem through a folder link": ["corpus", "-o", "dirlink/box.json"],
    "-o the .jsonl input": ["lines.jsonl", "-o", "lines.jsonl"],
    "-o a hard link to an input": ["corpus", "-o", "hard.json"],
    "-o a symbolic link to an input": ["corpus", "-o", "soft.json"],
    "-o the oracle CSV": ["rows.csv", "-o", "rows.csv"],
    "-o a problem a CSV row names": ["rows.csv", "-o", "named.json"],
    "-o an existing file that is not a results file": ["corpus", "-o", "notes.txt"],
    "--cert-dir holding the inputs": ["corpus", "-o", "r.jsonl", "--cert-dir", "."],
    "--cert-dir an input folder": ["corpus", "-o", "r.jsonl", "--cert-dir", "corpus"],
    "--cert-dir a file": ["corpus", "-o", "r.jsonl", "--cert-dir", "notes.txt"],
}


@pytest.mark.parametrize("case", sorted(BATCH_CASES))
def test_batch_never_overwrites_an_input(corpus, capsys, case):
    before = _snapshot(corpus)
    assert main(["batch", *BATCH_CASES[case], "--workers", "1"]) == 2, case
    out, err = capsys.readouterr()
    assert out == "" and err.startswith("exactinv: ") and len(err.strip().splitlines()) == 1, err
    assert _snapshot(corpus) == before, case
    assert not (corpus / "r.jsonl").exists()


def test_a_certificate_target_that_is_not_a_certificate_is_refused(corpus, capsys):
    certs = corpus / "certs"
    certs.mkdir()
    (certs / "q0.cert.json").write_text("a file of the user's that happens to have this name\n")
    _age(corpus)
    before = _snapshot(corpus)
    assert main(["batch", "corpus", "-o", "r.jsonl", "--cert-dir", "certs", "--workers", "1"]) == 2
    assert "q0.cert.json: the file exists and is not an exactinv certificate" in capsys.readouterr().err
    assert _snapshot(corpus) == before and not (corpus / "r.jsonl").exists()


def test_same_file_sees_links_and_spellings(corpus):
    q0 = corpus / "corpus" / "q0.json"
    assert all(same_file(q0, corpus / x) for x in ("soft.json", "hard.json", "dirlink/q0.json", "corpus/../corpus/q0.json"))
    assert not same_file(q0, corpus / "corpus" / "box.json") and not same_file(q0, corpus / "absent.json")
    os.symlink(corpus / "absent-target.json", corpus / "dangling.json")
    assert same_file(corpus / "dangling.json", corpus / "absent-target.json")  # resolved even where nothing exists


def test_atomic_write_keeps_the_old_file_when_the_write_fails(tmp_path, monkeypatch):
    target = tmp_path / "c.json"
    target.write_text("old")
    os.utime(target, (OLD, OLD))

    def broken(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "fsync", broken)
    with pytest.raises(OSError):
        atomic_write(str(target), "new")
    assert target.read_text() == "old" and target.stat().st_mtime_ns == OLD * 10**9
    assert os.listdir(tmp_path) == ["c.json"]


def test_atomic_write_writes_through_a_link_and_keeps_the_umask_mode(tmp_path):
    real = tmp_path / "real.json"
    os.symlink(real, tmp_path / "link.json")
    atomic_write(str(tmp_path / "link.json"), "{}")
    assert real.read_text() == "{}" and (tmp_path / "link.json").is_symlink()
    mask = os.umask(0)
    os.umask(mask)
    assert real.stat().st_mode & 0o777 == 0o666 & ~mask
    shutil.rmtree(tmp_path)
