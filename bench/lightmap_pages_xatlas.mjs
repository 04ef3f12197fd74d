// xatlas (npm xatlasjs) packing one mesh as a lightmap, for
// bench/lightmap_pages.py: reads {"V", "F", "padding", "resolution",
// "texels_per_unit"} as JSON, runs xatlas with its default chart options and
// those pack options (texelsPerUnit, resolution: the page side), and prints
// {"pages": atlasCount, "width", "height", "seconds"} as JSON.
import { readMesh, xatlasApi } from "./xatlas_api.mjs";

const mesh = readMesh(process.argv[2]);
const api = await xatlasApi();
const t0 = process.hrtime.bigint();
api.createAtlas();
if (!api.addMesh(new Uint16Array(mesh.F), new Float32Array(mesh.V))) throw new Error("xatlas refused the mesh");
api.generateAtlas({}, { padding: mesh.padding, resolution: mesh.resolution, texelsPerUnit: mesh.texels_per_unit }, false);
const seconds = Number(process.hrtime.bigint() - t0) / 1e9;
const atlas = api.xatlas.getAtlas();
console.log(JSON.stringify({ pages: atlas.atlasCount, width: atlas.width, height: atlas.height, seconds }));
api.destroyAtlas();
