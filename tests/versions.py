"""Certificates of the older versions: a version 3 certificate (H and H~ sparse) rewritten as
version 1 or 2 (H and H~ dense), for the tests that old certificates stay checkable."""

from __future__ import annotations

import copy

SPARSE_KEYS = ("H",)  # the m x m matrices version 3 writes sparse (on these claims and robust vertex records)


def dense_of(H: dict) -> list[list[str]]:
    """The dense rows of a version 3 sparse matrix (missing entries are "0")."""
    rows = H["sparse"]
    out = [["0"] * len(rows) for _ in rows]
    for i, row in enumerate(rows):
        for k, v in row:
            out[i][k] = v
    return out


def as_version(cert: dict, version: int) -> dict:
    """A copy of ``cert`` as ``version`` (1 or 2): every sparse H dense.  Version 1 has no dt;
    the caller removes it when the certificate has one."""
    out = copy.deepcopy(cert)
    out["version"] = version

    def fix(record: dict) -> None:
        if isinstance(record.get("H"), dict):
            record["H"] = dense_of(record["H"])
        for vertex in record.get("vertices", []) if record.get("type") == "robust_threshold" else []:
            fix(vertex)

    for claim in out["claims"]:
        fix(claim)
    return out
