"""The on-disk cache (synth.fingerprint): a hit gives the stored value, a changed key rebuilds, a damaged file is
rebuilt, "off" disables it, and stale versions are pruned."""

from __future__ import annotations

from synth import fingerprint as F


def test_cache_hit_miss_damage_and_off(tmp_path, monkeypatch):
    monkeypatch.setenv("SYNTH_CACHE_DIR", str(tmp_path))
    calls = []

    def build():
        calls.append(1)
        return {"value": len(calls)}
    assert F.cached("x", ["a"], build) == {"value": 1}
    assert F.cached("x", ["a"], build) == {"value": 1} and len(calls) == 1   # read back, not rebuilt
    assert F.cached("x", ["b"], build) == {"value": 2}                        # another key: built
    for f in tmp_path.glob("x-*.pickle"):
        f.write_bytes(b"not a pickle")
    assert F.cached("x", ["a"], build) == {"value": 3}                        # damaged: rebuilt
    monkeypatch.setenv("SYNTH_CACHE_DIR", "off")
    assert F.cached("x", ["a"], build) == {"value": 4}


def test_stale_versions_are_pruned(tmp_path, monkeypatch):
    monkeypatch.setenv("SYNTH_CACHE_DIR", str(tmp_path))
    for k in range(F._KEEP + 3):
        F.cached("y", [str(k)], lambda: k)
    assert len(list(tmp_path.glob("y-*.pickle"))) == F._KEEP


def test_catalog_hash_changes_with_a_user_catalog(tmp_path):
    base = F.catalogs_sha256()
    assert F.catalogs_sha256([tmp_path]) == base            # an empty folder reads no other data
    (tmp_path / "ball_bearings.csv").write_text("designation,source\nX,me\n")
    assert F.catalogs_sha256([tmp_path]) != base
