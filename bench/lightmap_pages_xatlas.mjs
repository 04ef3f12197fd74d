// xatlas (npm xatlasjs) packing one mesh as a lightmap, for
// bench/lightmap_pages.py: reads {"V", "F", "padding", "resolution",
// "texels_per_unit"} as JSON, runs xatlas with its default chart options and
// those pack options (texelsPerUnit, resolution: the page side), and prints
// {"pages": atlasCount, "width", "height", "seconds"} as JSON.
// Indices into xatlas are 16-bit (xatlasjs's createMesh): under 65,536 vertices.
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import { Api } from "xatlasjs/dist/node/api.mjs";

const require = createRequire(import.meta.url);
const createXAtlasModule = (await import("xatlasjs/dist/node/xatlas.js")).default;
const mesh = JSON.parse(readFileSync(process.argv[2], "utf8"));
const nv = mesh.V.length / 3;
if (nv >= 65536) throw new Error(`${nv} vertices: xatlasjs takes 16-bit indices`);
const XAtlas = Api(createXAtlasModule);
const api = await new Promise((resolve) => {
  const a = new XAtlas(() => resolve(a), (path, dir) => require.resolve("xatlasjs/dist/node/" + path));
});
const t0 = process.hrtime.bigint();
api.createAtlas();
if (!api.addMesh(new Uint16Array(mesh.F), new Float32Array(mesh.V))) throw new Error("xatlas refused the mesh");
api.generateAtlas({}, { padding: mesh.padding, resolution: mesh.resolution, texelsPerUnit: mesh.texels_per_unit }, false);
const seconds = Number(process.hrtime.bigint() - t0) / 1e9;
const atlas = api.xatlas.getAtlas();
console.log(JSON.stringify({ pages: atlas.atlasCount, width: atlas.width, height: atlas.height, seconds }));
api.destroyAtlas();
