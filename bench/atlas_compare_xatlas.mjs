// xatlas (the npm package xatlasjs: xatlas compiled to WebAssembly) on one
// mesh, for bench/atlas_compare.py. Reads {"V": [x,y,z,...], "F": [i,j,k,...],
// "padding": P, "resolution": R} as JSON, runs xatlas with its default chart
// options and the same padding and resolution as `intrinsic atlas`, and writes
// an OBJ like ours: the input's vertices, one `vt` per xatlas output vertex
// (xatlasjs returns UVs divided by the atlas width and height; scaled here
// to the longer side instead, so charts keep their shape; as xatlas's own example writes them, no flip) and
// faces `f v/vt`, so `intrinsic metrics` measures both atlases the same way.
// Prints {"seconds": ..., "width", "height", "vertices_out"} as JSON.
import { writeFileSync } from "node:fs";
import { readMesh, xatlasApi } from "./xatlas_api.mjs";

const [input, output] = process.argv.slice(2);
const mesh = readMesh(input);
const nv = mesh.V.length / 3;
const api = await xatlasApi();
const t0 = process.hrtime.bigint();
api.createAtlas();
if (!api.addMesh(new Uint16Array(mesh.F), new Float32Array(mesh.V))) throw new Error("xatlas refused the mesh");
api.generateAtlas({}, { padding: mesh.padding, resolution: mesh.resolution }, false);
const seconds = Number(process.hrtime.bigint() - t0) / 1e9;
// Read the result as 32-bit (getAtlas() truncates output indices to 16 bits).
const x = api.xatlas;
const atlas = x.getAtlas();
const d = x.getMeshData(api.meshes[0].meshId);
const n = d.newVertexCount;
const index = x.HEAPU32.slice(d.indexOffset / 4, d.indexOffset / 4 + d.newIndexCount);
const original = x.HEAPU32.slice(d.originalIndexOffset / 4, d.originalIndexOffset / 4 + n);
const uv = x.HEAPF32.slice(d.uvOffset / 4, d.uvOffset / 4 + 2 * n);
x.destroyMeshData(d);
d.subMeshes.delete();
const side = Math.max(atlas.width, atlas.height);
const lines = [`# xatlas (xatlasjs) atlas ${atlas.width}x${atlas.height}`];
for (let i = 0; i < nv; ++i) lines.push(`v ${mesh.V[3 * i]} ${mesh.V[3 * i + 1]} ${mesh.V[3 * i + 2]}`);
for (let i = 0; i < n; ++i) lines.push(`vt ${(uv[2 * i] * atlas.width) / side} ${(uv[2 * i + 1] * atlas.height) / side}`);
for (let f = 0; f < index.length; f += 3) {
  const c = [0, 1, 2].map((k) => `${original[index[f + k]] + 1}/${index[f + k] + 1}`);
  lines.push(`f ${c.join(" ")}`);
}
writeFileSync(output, lines.join("\n") + "\n");
api.destroyAtlas();
console.log(JSON.stringify({ seconds, width: atlas.width, height: atlas.height, vertices_out: n,
                             faces_out: index.length / 3 }));
