"""intrinsic.atlas(..., transfer_textures=True) then write_atlas bakes the
textures like `intrinsic atlas --transfer-textures`: same report entries and
the same baked image bytes, on the generated textured asset (glTF and OBJ);
without uv_set a glTF input is refused, as on the command line."""
import json
import subprocess

import pytest

import intrinsic

from conftest import cli_path  # noqa: E402


def run_cli(*args):
    return subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True)


@pytest.fixture
def asset(tmp_path):
    def make(name):
        path = tmp_path / name
        r = run_cli("generate", "textured", "--cells", "12", "--chart-cells", "1", "--texture-size", "512", "-o", path)
        assert r.returncode == 0, r.stderr
        return path
    return make


def test_gltf_keywords_match_the_cli(tmp_path, asset):
    src = asset("in.glb")
    rep = tmp_path / "cli.json"
    r = run_cli("atlas", src, "-o", tmp_path / "cli.glb", "--uv-set", "0", "--transfer-textures",
                "--texture-size", "256", "--report", rep, "-q")
    assert r.returncode == 0, r.stderr
    a = intrinsic.atlas(str(src), uv_set=0, transfer_textures=True, texture_size=256)
    textures = intrinsic.write_atlas(str(tmp_path / "py.glb"), a)
    cli = json.loads(rep.read_text())["textures"]
    assert textures == cli
    assert textures["baked"][0]["width"] == 256
    assert textures["baked"][0]["slot"] == "pbrMetallicRoughness/baseColorTexture"
    # The same document, byte for byte (the atlas and the bake are deterministic).
    assert (tmp_path / "py.glb").read_bytes() == (tmp_path / "cli.glb").read_bytes()


def test_obj_keywords_write_png_and_mtl(tmp_path, asset):
    src = asset("in.obj")
    a = intrinsic.atlas(str(src), transfer_textures=True, texture_size=128)
    textures = intrinsic.write_atlas(str(tmp_path / "out.obj"), a)
    assert [b["slot"] for b in textures["baked"]] == ["map_Kd"]
    assert (tmp_path / "out_textured_Kd.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "map_Kd out_textured_Kd.png" in (tmp_path / "out.mtl").read_text()


def test_without_transfer_nothing_is_returned(tmp_path, asset):
    a = intrinsic.atlas(str(asset("in.obj")))
    assert intrinsic.write_atlas(str(tmp_path / "out.obj"), a) is None
    assert not (tmp_path / "out.mtl").exists()


def test_gltf_transfer_needs_uv_set(asset):
    with pytest.raises(intrinsic.UsageError, match="uv_set"):
        intrinsic.atlas(str(asset("in.glb")), transfer_textures=True)


def test_bad_texture_size_is_a_usage_error(asset):
    with pytest.raises(intrinsic.UsageError, match="texture_size"):
        intrinsic.atlas(str(asset("in.glb")), uv_set=0, transfer_textures=True, texture_size=-3)
