"""`exactinv batch --cert-dir` and the batch's own outputs (issue 21, items 2, 3, 6).

* every certificate kept under --cert-dir is named after its problem's id and
  is verified again by `exactinv check`; its values are the record's;
* a re-run never reads its own results file (even a ``.json`` one inside the
  scanned folder) or its certificates as problems, and names every file it
  skipped (a ``.jsonl`` in a folder included);
* a resumed run's summary and exit code cover the whole results file.
"""

from __future__ import annotations

import json
import os
from fractions import Fraction

import pytest

distributed = pytest.importorskip("dask.distributed")

from exactinv.cli import main  # noqa: E402
from exactinv.interfaces.batch import run_batch  # noqa: E402
from exactinv.interfaces.batch.certdir import certificate_names  # noqa: E402

SEGMENT = {"G": [[1], [-1]], "b": [1, 1]}


@pytest.fixture(scope="module")
def scheduler():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address="127.0.0.1:0",
                                  silence_logs=40) as cluster:
        yield cluster.scheduler_address


def _decay(c: int) -> dict:
    """x' = -c x on [-1, 1], forward Euler: gamma* = c/2, largest threshold 2/c."""
    return {"name": f"decay-{c}", "system": {"A": [[-c]]}, "polyhedron": SEGMENT, "method": {"taylor": 1}}


def _write(folder, name: str, problem: dict) -> None:
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "w") as fh:
        json.dump(problem, fh)


def test_cert_dir_keeps_each_verified_certificate(scheduler, tmp_path, capsys):
    corpus = tmp_path / "corpus"
    for c in (1, 2, 4):
        _write(corpus, f"decay-{c}.json", _decay(c))
    _write(corpus / "sub", "decay-8.json", _decay(8))
    _write(corpus, "grows.json", {"system": {"A": [[1]]}, "polyhedron": SEGMENT, "method": {"taylor": 1}})
    (tmp_path / "more.jsonl").write_text(json.dumps(_decay(3)) + "\n")
    certs, out = corpus / "certs", corpus / "results.json"  # both inside the scanned folder
    args = ["batch", str(corpus), str(tmp_path / "more.jsonl"), "-o", str(out), "--cert-dir", str(certs),
            "--scheduler", scheduler]
    assert main(args) == 1  # grows.json: x' = x leaves [-1, 1] -- refuted
    text = capsys.readouterr().out
    assert "outcomes: proved 5, refuted 1 (exit code 1)" in text
    records = {json.loads(line)["id"]: json.loads(line) for line in out.read_text().splitlines()}
    ids = ["decay-1.json", "decay-2.json", "decay-4.json", "sub/decay-8.json", "grows.json", "decay-3"]
    assert sorted(records) == sorted(ids)
    names = certificate_names(ids)
    assert names["sub/decay-8.json"] == "sub%2Fdecay-8.cert.json" and names["decay-3"] == "decay-3.cert.json"
    assert sorted(os.listdir(certs)) == sorted(names.values())  # one file per problem, nothing else
    for i in ids:
        path = certs / names[i]
        assert records[i]["certificate"] == str(path) and "certificate_json" not in records[i]
        assert main(["check", str(path)]) == 0, i  # the kernel verifies each one again
        assert "certificate VERIFIED" in capsys.readouterr().out
        cert = json.loads(path.read_text())
        values = {claim["type"]: claim.get("value") for claim in cert["claims"]}
        assert values["gamma_star"] == records[i]["values"]["gamma_star"]
    for c in (1, 2, 4):
        assert records[f"decay-{c}.json"]["values"]["largest_threshold"] == str(Fraction(2, c))
    assert records["grows.json"]["outcome"] == "refuted" and records["grows.json"]["values"]["gamma_star"] == "oo"

    # the re-run reads neither its results file nor its certificates as problems, and says so
    before = {p: p.read_bytes() for p in certs.iterdir()}
    results = out.read_bytes()
    assert main(args) == 1
    captured = capsys.readouterr()
    assert out.read_bytes() == results  # nothing new: every problem already done
    assert {p: p.read_bytes() for p in certs.iterdir()} == before
    assert f"skipped {out}: the results file of this batch (--out), not a problem" in captured.err
    assert f"skipped 6 files in {certs}: inside --cert-dir" in captured.err  # one line for the folder
    assert "6 problems: 6 already in" in captured.out and "nothing left to run" in captured.out

    # a later batch with another results file: the old results and the certificates are still not problems
    other = tmp_path / "other.jsonl"
    (corpus / "notes.jsonl").write_text('{"not": "read"}\n')
    notes: list[str] = []
    summary = run_batch([corpus], other, scheduler=scheduler, progress=False, notice=notes.append)
    assert summary.total == 5 and summary.count("error") == 0
    why = dict(summary.ignored)
    assert why[str(out)] == "an exactinv batch results file, not a problem"
    assert all(why[str(certs / name)] == "an exactinv certificate, not a problem" for name in names.values())
    assert why[str(corpus / "notes.jsonl")].startswith("a .jsonl file inside a directory is not read")
    assert len(notes) == 3 and "not read: " in summary.table()  # the results file, the certificates, notes.jsonl
    assert f"skipped 6 files in {certs}: an exactinv certificate, not a problem" in notes


def test_a_resumed_batch_reports_the_whole_results_file(scheduler, tmp_path):
    corpus = tmp_path / "corpus"
    _write(corpus, "decay-1.json", _decay(1))
    _write(corpus, "broken.json", {"system": {"A": [[1]]}})  # bad input: no polyhedron
    out = tmp_path / "results.jsonl"
    first = run_batch([corpus], out, scheduler=scheduler, progress=False)
    assert (first.ran, first.exit_code) == (2, 2)
    _write(corpus, "decay-2.json", _decay(2))
    second = run_batch([corpus], out, scheduler=scheduler, progress=False)
    # this run did one problem, fine; the file still holds the earlier bad input: exit 2, counted
    assert (second.total, second.skipped, second.ran) == (3, 2, 1)
    assert second.records == 3 and second.count("ok") == 2 and second.count("error") == 1
    assert dict(second.outcomes) == {"proved": 2, "bad_input": 1} and second.exit_code == 2 and not second.ok
    assert main(["batch", str(corpus), "-o", str(out), "--scheduler", scheduler]) == 2


def test_an_old_results_file_without_outcomes_still_counts(scheduler, tmp_path):
    """Records written before outcomes were recorded: gamma* = oo is refuted, a failed status an error."""
    corpus = tmp_path / "corpus"
    _write(corpus, "decay-1.json", _decay(1))
    out = tmp_path / "results.jsonl"
    out.write_text('{"id": "old-a", "status": "ok", "values": {"gamma_star": "oo"}}\n'
                   '{"id": "old-b", "status": "timeout"}\n')
    summary = run_batch([corpus], out, scheduler=scheduler, progress=False)
    assert dict(summary.outcomes) == {"proved": 1, "refuted": 1, "error": 1} and summary.exit_code == 4
