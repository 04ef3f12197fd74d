// Surfaces the project makes itself: the README's default input, the test
// cases with known answers, and the benchmark meshes. All are irregularly
// sampled disks (rings of jittered points around a centre, stitched by
// angle), lifted onto a surface, or closed grids (sphere, torus, genus 2).
#pragma once

#include <cstdint>
#include <string>

#include "intrinsic/image.h"
#include "intrinsic/mesh_data.h"

namespace intrinsic {

struct GenerateOptions {
  int rings = 20;            // radial resolution; about 3 * rings^2 vertices
  double jitter = 0.3;       // fraction of the local spacing points are moved by (0 = regular)
  std::uint64_t seed = 1;
  double cap_angle = 1.2;    // cap: polar angle of the boundary (radians)
  double band_height = 0.6;  // band: half-height of the spherical band, |z| <= band_height
};

// A disk in the plane z = 0 (unit radius), irregular: the barycentric test case.
MeshData generate_flat_disk(const GenerateOptions& o);
// A cap of the unit sphere around the north pole, polar angle <= cap_angle.
MeshData generate_sphere_cap(const GenerateOptions& o);
// A wavy height field over the unit disk with denser sampling on one side:
// the default curved, irregular input.
MeshData generate_wavy_patch(const GenerateOptions& o);
// An annulus-like band of the unit sphere (|z| <= band_height) cut open along
// a meridian into a disk: the paper's Figure 7 case (a strip).
MeshData generate_sphere_strip(const GenerateOptions& o);
// Two disjoint flat disks side by side (a two-component file).
MeshData generate_two_disks(const GenerateOptions& o);

// Closed surfaces (no boundary), for `intrinsic atlas`. Regular
// grids jittered inside their cells, outward-oriented.
// A bumpy sphere (latitude-longitude grid with two poles, radius modulated):
// genus 0, Euler characteristic 2; about 2 * rings^2 vertices.
MeshData generate_bumpy_sphere(const GenerateOptions& o);
// A torus (radii 1 and 0.4): genus 1, Euler characteristic 0; 3 * rings^2 vertices.
MeshData generate_torus(const GenerateOptions& o);
// Two tori joined by a tube: genus 2, Euler characteristic -2; about 6 * rings^2 vertices.
MeshData generate_genus2(const GenerateOptions& o);

// A textured asset to re-atlas (src/mesh/textured_asset.cpp): a closed
// ellipsoid (radii 1, 0.9, 0.8; a cube's six faces, each a cells x cells grid,
// pushed onto it) cut into many tiny square charts (chart_cells x
// chart_cells grid cells each: 6 * (cells / chart_cells)^2 charts), each
// with its own UVs in a tile of a square grid, like a scan's or a badly
// packed game asset's layout. Its texture is textured_asset_colour of the
// surface point each texel shows (texels of a tile's gutter show the nearest
// point of the chart), so a baked texture can be checked against the formula.
struct TexturedAssetOptions {
  int cells = 32;          // grid cells along each cube face's edge: 12 * cells^2 triangles
  int chart_cells = 2;     // chart side in cells
  int texture_size = 1024; // the texture's side in texels
};
struct TexturedAsset {
  MeshData mesh;  // V, F (closed, outward), TC (OBJ convention: v up) and FTC per chart
  Image texture;  // RGB8, top row first
};
TexturedAsset generate_textured_asset(const TexturedAssetOptions& o);
// The texture's colour at a point of the surface, RGB in [0, 1]: smooth
// (each channel changes by at most 0.75 per unit of length).
Eigen::Vector3d textured_asset_colour(const Eigen::Vector3d& p);
// Writes the asset as .glb/.gltf (one primitive with POSITION, NORMAL,
// TEXCOORD_0, a material whose baseColorTexture is the PNG, embedded) or .obj
// (with NAME.mtl, map_Kd NAME.png beside it); all files or none.
void write_textured_asset(const std::string& path, const TexturedAsset& asset);

// Shapes whose good atlas layout is known (src/generate/generate_cad.cpp), for
// the atlas's layout tests: unjittered grids unless said, every vertex shared
// by all the faces meeting at it, consistently oriented, closed ones outward.
// A machined plate as CAD exporters write it: 4 x 3 x 0.2 around the origin,
// 8 x 6 square cells whose borders carry k = max(1, 2 * rings / 5) points a
// side; 16 of them drilled through (radius 0.3 of the side; a diagonal
// pattern, seed % 3 shifts it). A drilled cell's top is its border joined to
// the hole's 4k-point circle, a solid cell's is cut in diagonal bands: long
// thin triangles. Closed, genus 16 (Euler characteristic -30).
MeshData generate_drilled_plate(const GenerateOptions& o);
// A closed box 2 x 1 x 0.5 around the origin, each side a grid of squares of
// side 0.5 / max(1, rings / 3), each cut into two triangles: genus 0.
MeshData generate_box(const GenerateOptions& o);
// An open flat L in z = 0, [0,3]x[0,1] and [0,1]x[0,3], with the square hole
// [0.4,0.6]^2 in its corner block: a grid of squares, 5 * max(1, rings / 8)
// to a unit, the hole's cells missing. Two boundary loops.
MeshData generate_l_panel(const GenerateOptions& o);
// An open flat panel [0,2]^2 in z = 0 (a grid of max(2, rings)^2 squares)
// and a strip 0.1 wide folded up at 90 degrees along its edge y = 2 (the
// points (x, 2, z), z in [0, 0.1]), one sheet sharing that edge's vertices.
MeshData generate_panel_with_strip(const GenerateOptions& o);
// An open tube of radius 0.2 and length 4 along x (x in [-2, 2]; two boundary
// loops): max(6, 6 * rings / 5) points around, each ring turned half a step
// from the last, near-equilateral triangles.
MeshData generate_long_cylinder(const GenerateOptions& o);
// The rectangle [0,2]x[0,1] (a grid of 2n x n squares, n = max(1, rings / 2),
// jittered: side points along their side only, corners fixed) turned 30
// degrees counter-clockwise about the z axis: its sides are not on the axes.
MeshData generate_flat_rectangle(const GenerateOptions& o);

// By name: "flat", "cap", "wave", "strip", "two-disks", "sphere", "torus",
// "genus2", "plate", "box", "l-panel", "panel-strip", "cylinder",
// "rectangle". Throws Error(Usage).
MeshData generate_surface(const std::string& name, const GenerateOptions& o);

// A machine-like asset of many parts (src/generate/generate_parts.cpp), the
// scale test of `intrinsic atlas` (generate surface "parts"): `parts`
// disjoint pieces of varied shape and size, side by side on a grid, each a
// jittered grid of its own. Closed pieces are outward-oriented.
enum class PartShape {
  Ellipsoid,   // closed, genus 0 (bumpy, squashed): Euler characteristic 2
  RoundedBox,  // closed, genus 0 (a superellipsoid): 2
  Torus,       // closed, genus 1 (a ring, a washer): 0
  Tube,        // open, two boundary loops (a pipe, bent): 0
  Plate,       // open, one boundary loop (a wavy bracket): 1
  Bowl,        // open, one boundary loop (a cap, a cup): 1
};
struct PartsOptions {
  int parts = 500;
  long faces = 1000000;  // about this many in all (each part at least 48)
  std::uint64_t seed = 1;
};
struct GeneratedParts {
  MeshData mesh;
  std::vector<PartShape> shape;  // per part
  std::vector<int> face_part;    // per face of mesh.F; parts are in face order, one block each
};
// Throws Error(Usage) for parts outside [1, 100000] or faces outside [48 * parts, 1e8].
GeneratedParts generate_parts(const PartsOptions& o);

}  // namespace intrinsic
