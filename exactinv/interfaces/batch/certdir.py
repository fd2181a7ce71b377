"""``exactinv batch --cert-dir DIR``: one certificate file per problem.

The file is named after the problem's id -- ``ID.cert.json`` with the id
percent-encoded (``/`` and every character other than letters, digits,
``-``, ``_`` and ``.`` as ``%XX``, a leading dot too), so that two ids never
share a file and no id leaves DIR; a ``.json`` at the end of the id is
dropped unless another id would then take the same name.  Certificates are
written on the machine that runs the batch (workers need no shared file
system), atomically, and only once the kernel verified them (with
``--no-check``: unverified, as the user asked).  Every target is checked
before any work: none is an input or the results file, and none replaces a
file that is not an exactinv certificate.

>>> certificate_names(["box.json", "sub/box.json", "poly #1", "box"])
{'box.json': 'box.json.cert.json', 'sub/box.json': 'sub%2Fbox.cert.json', 'poly #1': 'poly%20%231.cert.json', 'box': 'box.cert.json'}
"""  # noqa: E501 (doctest output)

from __future__ import annotations

import hashlib
import os
from collections import Counter
from typing import Iterable
from urllib.parse import quote

from ...errors import InvalidInput
from ..files import is_certificate, refuse_foreign, refuse_inputs

__all__ = ["certificate_names", "prepare_cert_dir"]

_SUFFIX = ".cert.json"
_MAX = 200  # bytes of a file name before it is shortened (most file systems allow 255)


def _encode(text: str) -> str:
    name = quote(text, safe="-_.")
    if name.startswith("."):
        name = "%2E" + name[1:]
    if len(name.encode()) > _MAX:
        name = name[:_MAX - 17] + "-" + hashlib.sha256(text.encode()).hexdigest()[:16]
    return name


def certificate_names(ids: Iterable[str]) -> dict[str, str]:
    """The file name of each id's certificate (distinct for distinct ids; see the module docstring).

    >>> certificate_names(["a.json", "../up", ".hidden"])
    {'a.json': 'a.cert.json', '../up': '%2E.%2Fup.cert.json', '.hidden': '%2Ehidden.cert.json'}
    """
    ids = list(ids)
    short = {i: _encode(i[:-5] if i.lower().endswith(".json") else i) for i in ids}
    full = {i: _encode(i) for i in ids}
    owner = {name: i for i, name in full.items()}
    count = Counter(short.values())
    names = {i: (full[i] if count[short[i]] > 1 or owner.get(short[i], i) != i else short[i]) + _SUFFIX
             for i in ids}
    if len(set(names.values())) != len(names):  # only a hash collision of shortened names could get here
        raise InvalidInput("--cert-dir: two problem ids give the same certificate file name; rename one")
    return names


def prepare_cert_dir(cert_dir: str, ids: Iterable[str], inputs: Iterable[str], out: str) -> dict[str, str]:
    """The path of each id's certificate in ``cert_dir``, after refusing (InvalidInput) a
    ``cert_dir`` that is a file or an input, and any target that is an input, the
    results file, or an existing file other than an exactinv certificate.  Creates
    ``cert_dir`` (not its parents) if missing -- after every check has passed.

    >>> import tempfile
    >>> d = tempfile.mkdtemp(); problem = os.path.join(d, "box.json"); open(problem, "w").close()
    >>> paths = prepare_cert_dir(os.path.join(d, "certs"), ["box.json"], [problem], os.path.join(d, "r.jsonl"))
    >>> os.path.relpath(paths["box.json"], d), os.path.isdir(os.path.join(d, "certs"))
    ('certs/box.cert.json', True)
    >>> prepare_cert_dir(d, ["box"], [os.path.join(d, "box.cert.json")], "r.jsonl")  # a problem named box.cert.json
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: --cert-dir ...box.cert.json: this is the input ...box.cert.json; exactinv never overwrites an input (choose another file name)
    """  # noqa: E501 (doctest output)
    if os.path.exists(cert_dir) and not os.path.isdir(cert_dir):
        raise InvalidInput(f"--cert-dir {cert_dir}: exists and is not a directory")
    parent = os.path.dirname(os.path.abspath(cert_dir))
    if not os.path.isdir(parent):
        raise InvalidInput(f"--cert-dir {cert_dir}: the directory {parent} does not exist")
    inputs = list(inputs)
    paths = {i: os.path.join(cert_dir, name) for i, name in certificate_names(ids).items()}
    for path in paths.values():
        refuse_inputs(path, "--cert-dir", [*inputs, out])
        refuse_foreign(path, "--cert-dir", is_certificate, "an exactinv certificate")
    os.makedirs(cert_dir, exist_ok=True)
    if not os.access(cert_dir, os.W_OK | os.X_OK):
        raise InvalidInput(f"--cert-dir {cert_dir}: not writable")
    return paths
