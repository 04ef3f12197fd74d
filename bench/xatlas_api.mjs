// xatlas (npm xatlasjs: xatlas compiled to WebAssembly) loaded once for the
// bench scripts, with a mesh read from the JSON they are given: {"V":
// [x,y,z,...], "F": [i,j,k,...], ...}. Indices into xatlas are 16-bit
// (xatlasjs's createMesh), so meshes of 65,536 vertices or more are refused.
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import { Api } from "xatlasjs/dist/node/api.mjs";

const require = createRequire(import.meta.url);
const createXAtlasModule = (await import("xatlasjs/dist/node/xatlas.js")).default;

export function readMesh(path) {
  const mesh = JSON.parse(readFileSync(path, "utf8"));
  const nv = mesh.V.length / 3;
  if (nv >= 65536) throw new Error(`${nv} vertices: xatlasjs takes 16-bit indices`);
  return mesh;
}

// The API object once its WebAssembly module is ready.
export async function xatlasApi() {
  const XAtlas = Api(createXAtlasModule);
  return new Promise((resolve) => {
    const a = new XAtlas(() => resolve(a), (path, dir) => require.resolve("xatlasjs/dist/node/" + path));
  });
}
