// The 2D view's mesh layer in WebGL: the layout's edges, the faces coloured
// by distortion bin (optional) and the flipped faces in red, all drawn from
// one float32 UV vertex buffer that a new answer updates with bufferSubData
// (the edge index buffer never changes; the face index buffer is refilled
// only with the faces to fill). The handles, boundary, constraints and colour
// bar stay on the 2D canvas above it (view2d.js). Drawing every triangle as a
// canvas path cost ~100 ms a frame at 32k vertices in headless Chromium.
import { $, state } from './state.js';
import { rgbOf, scaleOf } from './distortion.js';
import { program } from './gl.js';

export const BINS = 16;
export const VMAX = { angle: 3, area: 4 };

const VS = `attribute vec2 uv; uniform vec4 win;
void main() { gl_Position = vec4(win.x + uv.x * win.z, win.y + uv.y * win.w, 0.0, 1.0); }`;
const FS = `precision mediump float; uniform vec4 colour; void main() { gl_FragColor = colour; }`;

const layer = { gl: null, prog: null, uv: null, edges: null, edgeCount: 0, faces: null, faceIndex: null, failed: false };

// Each mesh edge once, as pairs of vertices.
function edgeList(tri) {
  const seen = new Set(), out = [];
  for (let f = 0; f < tri.length; f += 3)
    for (let k = 0; k < 3; k++) {
      const a = tri[f + k], b = tri[f + (k + 1) % 3], key = a < b ? a * 4294967296 + b : b * 4294967296 + a;
      if (!seen.has(key)) { seen.add(key); out.push(a, b); }
    }
  return Uint32Array.from(out);
}

function init() {
  const gl = $('view2dgl').getContext('webgl', { antialias: false, alpha: false });
  if (!gl || (!gl.getExtension('OES_element_index_uint') && state.mesh.vertices > 65535)) {
    layer.failed = true;
    $('error').textContent = 'WebGL (with 32-bit indices) is not available: 2D layout not drawn';
    return;
  }
  const prog = program(gl, VS, FS);
  Object.assign(layer, { gl, prog, win: gl.getUniformLocation(prog, 'win'), colour: gl.getUniformLocation(prog, 'colour') });
  layer.uv = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, layer.uv);
  gl.bufferData(gl.ARRAY_BUFFER, 8 * state.mesh.vertices, gl.DYNAMIC_DRAW);
  const edges = edgeList(state.mesh.triangles);
  layer.edges = gl.createBuffer();
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, layer.edges);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, edges, gl.STATIC_DRAW);
  layer.edgeCount = edges.length;
  layer.faces = gl.createBuffer();
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, layer.faces);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, 4 * state.mesh.triangles.length, gl.DYNAMIC_DRAW);
  layer.faceIndex = new Uint32Array(state.mesh.triangles.length);
}

// A new layout (float32 UVs, 2n): into the vertex buffer.
export function uploadLayout(uv32) {
  if (!layer.gl && !layer.failed) init();
  if (!layer.gl) return;
  const gl = layer.gl;
  gl.bindBuffer(gl.ARRAY_BUFFER, layer.uv);
  gl.bufferSubData(gl.ARRAY_BUFFER, 0, uv32);
}

// The faces to fill, grouped: [{first, count, rgba}] over layer.faceIndex
// (distortion bins when colouring, then the flipped faces).
function faceGroups(colour, values) {
  const uv = state.uv, tri = state.mesh.triangles, m = tri.length / 3;
  const binOf = new Int8Array(m), counts = new Int32Array(BINS + 1);
  for (let f = 0; f < m; f++) {
    const a = 2 * tri[3 * f], b = 2 * tri[3 * f + 1], c = 2 * tri[3 * f + 2];
    // Counter-clockwise in the (u, v) plane is positive; flipped faces go to bin BINS.
    const flipped = (uv[b] - uv[a]) * (uv[c + 1] - uv[a + 1]) - (uv[b + 1] - uv[a + 1]) * (uv[c] - uv[a]) < 0;
    const k = flipped ? BINS : values ? Math.min(BINS - 1, Math.floor(scaleOf(values[f], VMAX[colour]) * BINS)) : -1;
    binOf[f] = k;
    if (k >= 0) counts[k]++;
  }
  const start = new Int32Array(BINS + 1), groups = [];
  for (let k = 0, s = 0; k <= BINS; k++) {
    start[k] = s;
    if (counts[k]) {
      const rgba = k === BINS ? [220 / 255, 0, 0, 0.6] : [...rgbOf((k + 0.5) / BINS).map((x) => x / 255), 1];
      groups.push({ first: 3 * s, count: 3 * counts[k], rgba });
    }
    s += counts[k];
  }
  const out = layer.faceIndex;
  for (let f = 0; f < m; f++) {
    const k = binOf[f];
    if (k < 0) continue;
    const j = 3 * start[k]++;
    out[j] = tri[3 * f]; out[j + 1] = tri[3 * f + 1]; out[j + 2] = tri[3 * f + 2];
  }
  return { groups, used: groups.reduce((s, g) => Math.max(s, g.first + g.count), 0) };
}

// Draws the layer for the window `v` (view2d.js: origin and side in CSS pixels).
export function drawLayout(v, colour, values) {
  if (!layer.gl && !layer.failed) init();
  const gl = layer.gl;
  if (!gl) return;
  const c = gl.canvas, dpr = window.devicePixelRatio || 1;
  const w = Math.round(c.clientWidth * dpr), h = Math.round(c.clientHeight * dpr);
  if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
  gl.viewport(0, 0, w, h);
  gl.clearColor(1, 1, 1, 1);
  gl.clear(gl.COLOR_BUFFER_BIT);
  if (!state.uv) return;
  gl.useProgram(layer.prog);
  // Clip coordinates of u, v: x = ox + u side (CSS pixels) -> 2 x / width - 1; y likewise, downwards.
  const cw = c.clientWidth, ch = c.clientHeight;
  gl.uniform4f(layer.win, 2 * v.ox / cw - 1, 1 - 2 * v.oy / ch, 2 * v.side / cw, 2 * v.side / ch);
  const loc = gl.getAttribLocation(layer.prog, 'uv');
  gl.bindBuffer(gl.ARRAY_BUFFER, layer.uv);
  gl.enableVertexAttribArray(loc);
  gl.vertexAttribPointer(loc, 2, gl.FLOAT, false, 0, 0);
  gl.enable(gl.BLEND);
  gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
  const { groups, used } = faceGroups(colour, values);
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, layer.faces);
  if (used) gl.bufferSubData(gl.ELEMENT_ARRAY_BUFFER, 0, layer.faceIndex.subarray(0, used));
  for (const g of groups) {
    gl.uniform4fv(layer.colour, g.rgba);
    gl.drawElements(gl.TRIANGLES, g.count, gl.UNSIGNED_INT, 4 * g.first);
  }
  gl.uniform4fv(layer.colour, values ? [60 / 255, 60 / 255, 80 / 255, 0.35] : [0x88 / 255, 0x96 / 255, 0xaa / 255, 0.8]);
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, layer.edges);
  gl.drawElements(gl.LINES, layer.edgeCount, gl.UNSIGNED_INT, 0);
}
