#!/usr/bin/python3
"""Side-by-side pictures of the atlases of bench/atlas_compare.py: for each
mesh, one PNG with a column per tool (intrinsic | xatlas | Blender Smart UV
Project), the checkerboard on the surface on top and the UV layout (a colour
per chart, folded or overlapping triangles red) under it, each panel drawn by
the project's own renderer (`intrinsic render --mode checker` and
`--mode layout`, which read the OBJs' per-corner UVs), and a caption per
tool with the figures atlas_compare.py measures. A bench artefact, not a
test: it needs Pillow (Debian's python3-pil) to put the panels together.

The checker squares are counted across each atlas's UV square (--squares),
so every tool gets the same texture resolution and a person sees what a
texture of that size would look like on each: square and even is good,
stretched, sheared or varying square sizes are distortion, cuts through the
pattern are seams.

Usage: bench/atlas_pictures.py [--cli build/intrinsic] [--out docs/images]
          [--blender blender] [--node node] [--size 480] [--squares 32] [MESH ...]
Without meshes: truck, spot, screwdriver (shared assets) and a generated
torus (`intrinsic generate torus`). Writes OUT/atlas-compare-NAME.png.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

from PIL import Image, ImageDraw, ImageFont

import atlas_compare as ac

TOOL_TITLES = {"intrinsic": "intrinsic atlas", "xatlas": "xatlas (xatlasjs)", "blender": "Blender 3.4 Smart UV Project"}
# A view per default mesh (azimuth, elevation about world z; at elevation 90
# world y is up, for truck's y-up model). Never "auto" for a comparison: the
# automatic view follows the mean normal of each tool's OBJ, and an atlas
# that re-orients faces (ours on truck) would be seen from elsewhere.
# Anything else gets the renderer's fallback three-quarter view.
VIEWS = {"truck": "0,90", "spot": "-30,25", "screwdriver": "-30,25", "torus": "-30,25"}
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"


def render(cli, obj, png, mode, size, squares, view):
    cmd = [cli, "render", obj, "-o", png, "--mode", mode, "--size", f"{size},{size}", "-q"]
    if mode == "checker":
        cmd += ["--squares", str(squares), "--view", view]
    subprocess.run(cmd, check=True)
    return Image.open(png).convert("RGB")


def caption(r, why):
    if r is None:
        return [why]
    return [f"{r['charts']} charts, utilization {r['utilization']:.1%}",
            f"Sander L2 {r['sander_l2']:.3f}, face stretch p95 {r['face_stretch_p95']:.3f}",
            f"seam/sqrt(area) {r['seam_per_sqrt_area']:.3g}, overlaps {r['overlapping']}, {r['seconds']:.2f} s"]


def font(size):
    try:
        return ImageFont.truetype(FONT, size)
    except OSError:
        return ImageFont.load_default()


def compose(name, columns, size, path):
    """columns: [(title, caption lines, checker image or None, layout image or None)]."""
    title_f, text_f = font(max(14, size // 24)), font(max(11, size // 36))
    line = text_f.getbbox("Ag")[3] + 4
    head = title_f.getbbox("Ag")[3] + 8 + 3 * line + 8
    W, H = size * len(columns), head + 2 * size + 30
    page = Image.new("RGB", (W, H), "white")
    d = ImageDraw.Draw(page)
    for i, (title, lines, checker, layout) in enumerate(columns):
        x = i * size
        d.text((x + 10, 6), title, fill="black", font=title_f)
        for k, t in enumerate(lines):
            d.text((x + 10, title_f.getbbox("Ag")[3] + 14 + k * line), t, fill=(40, 40, 40), font=text_f)
        for j, im in enumerate((checker, layout)):
            if im is not None:
                page.paste(im.resize((size, size)) if im.size != (size, size) else im, (x, head + j * size))
        if i:
            d.line([(x, 0), (x, H - 30)], fill=(180, 180, 180), width=1)
    d.text((10, H - 24), f"{name}: checker on the surface (top), UV layout, a colour per chart, folded or overlapping triangles red (bottom)",
           fill=(80, 80, 80), font=text_f)
    # 256 colours keep a picture of the repository's docs under ~0.5 MB.
    page.quantize(256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE).save(path, optimize=True)


def picture(args, mesh, name, tools, tmp):
    produced = ac.produce_all(args, mesh, tmp, tools, 1)
    rows = ac.measure_all(args.cli, name, produced)
    columns = []
    for tool, (obj, _) in produced.items():
        r, why = rows[tool]
        ims = [None, None]
        if obj is not None:
            ims = [render(args.cli, obj, os.path.join(tmp, f"{tool}-{m}.png"), m, args.size, args.squares,
                          VIEWS.get(name, "-30,25")) for m in ("checker", "layout")]
        columns.append((TOOL_TITLES[tool], caption(r, why), *ims))
    out = os.path.join(args.out, f"atlas-compare-{name}.png")
    compose(name, columns, args.size, out)
    return out


def default_meshes(cli, tmp):
    d = os.path.join(os.environ.get("INTRINSIC_SHARED_MESHES", os.path.join(ac.ROOT, "..", "shared", "meshes")),
                     "assets")
    torus = os.path.join(tmp, "torus.obj")
    subprocess.run([cli, "generate", "torus", "-o", torus, "--rings", "20"], check=True, stdout=subprocess.DEVNULL)
    return [os.path.join(d, n) for n in ("truck.obj", "spot.obj", "screwdriver.off")] + [torus]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="*")
    ap.add_argument("--cli", default=os.path.join(ac.ROOT, "build", "intrinsic"))
    ap.add_argument("--out", default=os.path.join(ac.ROOT, "docs", "images"))
    ap.add_argument("--node", default="node")
    ap.add_argument("--blender", default=shutil.which("blender") or "")
    ap.add_argument("--padding", type=float, default=2)
    ap.add_argument("--resolution", type=int, default=1024)
    ap.add_argument("--size", type=int, default=480, help="panel side in pixels")
    ap.add_argument("--squares", type=int, default=32, help="checker squares across each atlas's UV square")
    args = ap.parse_args()
    tools = ["xatlas"] + (["blender"] if args.blender else [])
    with tempfile.TemporaryDirectory() as tmp:
        meshes = args.meshes or default_meshes(args.cli, tmp)
        for mesh in meshes:
            name = os.path.basename(mesh).split(".")[0]
            work = os.path.join(tmp, name)
            os.makedirs(work, exist_ok=True)
            print(picture(args, mesh, name, tools, work), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
