// The editor page's shared state (one object, read and written by the other
// modules) and the element lookup. window.__intrinsic exposes it to the
// browser test and the bench.
export const $ = (id) => document.getElementById(id);

export const session = Array.from(crypto.getRandomValues(new Uint8Array(12)),
  (b) => b.toString(16).padStart(2, '0')).join('');

export const state = {
  mesh: null,          // GET /api/mesh
  uv: null,            // Float64Array 2n, what is drawn (Float32Array while dragging)
  answer: null,        // the last answer drawn
  moves: new Map(),    // fixed boundary: vertex -> [u, v]
  pins: null,          // natural map: [[vertex, u, v], ...]
  // Same shape as a constraint file (docs/formats.md); barycentrics in the file's corner order.
  constraints: { points: [], lines: [] },
  linePath: null,      // a line being drawn: [{face, bary, uv}, ...]
  selection: null,     // boundary range: {from, to} indices along the outer loop
  dragging: null,      // what the mouse holds (interact.js)
  preview: null,       // {kind: 'blend', lambda} while the lambda slider shows a blend of solutions
  inFlight: false, queued: null, lastRequest: null,
  updates: 0, frames: 0, error: null,
  latencies: [],       // mouse event to the frame after the new UVs are drawn (ms)
  drawTimes: [],       // the frame callback's own time (uploads, 2D overlay, GL calls; ms)
  roundTrips: [],      // /api/solve request to parsed JSON answer, as the page sees it (ms)
  phases: [],          // per /api/solve answer: {wait, headers, body, server} (ms; api.js)
  uploadTimes: [],     // the frame callback's vertex buffer uploads (ms; part of drawTimes)
};

// Outer loop index of each vertex (-1: not on it).
export function loopIndex() {
  if (!state.loopIndex) {
    state.loopIndex = new Int32Array(state.mesh.vertices).fill(-1);
    state.mesh.boundary_loops[0].forEach((v, k) => { state.loopIndex[v] = k; });
  }
  return state.loopIndex;
}

export const natural = () => $('boundary').value === 'natural';
