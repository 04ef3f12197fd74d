// What the mouse does: in the 2D view, drag a boundary vertex (or a
// shift-click-selected range of the outer loop) with a cosine falloff over
// the neighbouring vertices, a pin (natural map) or a constraint target; in
// the 3D view, a click adds a point constraint or a point of the line being
// drawn (a constraint starts where the map already puts it, so adding one
// changes nothing until its target is dragged).
import { $, loopIndex, state } from './state.js';
import { setError, solve } from './api.js';
import { handles, toUV, view2d } from './view2d.js';
import { pick } from './view3d.js';
import { draw } from './view.js';

function nearestHandle(x, y) {
  let best = null, bestD = 8;  // pixels
  for (const h of handles()) {
    const d = Math.hypot(h.x - x, h.y - y);
    if (d < bestD - 1e-9) { best = h; bestD = d; }
  }
  return best;
}

const mouseUV = (e) => {
  const rect = $('view2d').getBoundingClientRect();
  return toUV(view2d(), e.clientX - rect.left, e.clientY - rect.top);
};

// Weight of outer-loop index j for a drag of the range [from, to] with a
// falloff over `width` vertices on each side: 1 inside, cosine down to 0.
export function falloffWeights(from, to, width, n) {
  const out = [];
  const len = (to - from + n) % n;
  width = Math.max(0, Math.min(width, Math.floor((n - len - 1) / 2)));  // the falloff never wraps onto the range
  for (let d = -width; d <= len + width; d++) {
    const outside = d < 0 ? -d : d > len ? d - len : 0;
    out.push([(from + d + n) % n, outside ? 0.5 * (1 + Math.cos(Math.PI * outside / (width + 1))) : 1]);
  }
  return out;
}

function startBoundaryDrag(h, e) {
  const loop = state.mesh.boundary_loops[0], n = loop.length, k = loopIndex()[h.vertex];
  const sel = state.selection;
  const inSel = sel && (k - sel.from + n) % n <= (sel.to - sel.from + n) % n;
  const [from, to] = inSel ? [sel.from, sel.to] : [k, k];
  if (!inSel) state.selection = null;
  const width = Number($('falloff').value);
  const affected = falloffWeights(from, to, width, n).map(([j, w]) => {
    const v = loop[j];
    return { v, w, start: [state.uv[2 * v], state.uv[2 * v + 1]] };
  });
  state.dragging = { kind: 'boundary', affected, mouse: mouseUV(e) };
}

function select(h) {
  const n = state.mesh.boundary_loops[0].length, k = loopIndex()[h.vertex];
  if (!state.selection || state.selection.anchor === undefined) { state.selection = { from: k, to: k, anchor: k }; return; }
  const a = state.selection.anchor;
  // The shorter way round the loop from the anchor.
  state.selection = (k - a + n) % n <= n / 2 ? { from: a, to: k, anchor: a } : { from: k, to: a, anchor: a };
}

function dragTo(e) {
  const d = state.dragging, uv = mouseUV(e), stamp = e.timeStamp;
  if (d.kind === 'boundary') {
    const du = uv[0] - d.mouse[0], dv = uv[1] - d.mouse[1];
    for (const a of d.affected) state.moves.set(a.v, [a.start[0] + a.w * du, a.start[1] + a.w * dv]);
  } else if (d.kind === 'pin') {
    const pin = state.pins.find((p) => p[0] === d.vertex);
    pin[1] = uv[0];
    pin[2] = uv[1];
  } else if (d.kind === 'point') {
    state.constraints.points[d.index].uv = uv;
  } else if (d.kind === 'line') {
    state.constraints.lines[d.index].to[d.k] = uv;
  }
  d.moved = true;
  solve(stamp);
}

export function dragControls() {
  const c = $('view2d');
  c.addEventListener('mousedown', (e) => {
    const h = nearestHandle(e.pageX, e.pageY);
    if (!h) return;
    e.preventDefault();
    if (h.kind === 'boundary' && e.shiftKey) { select(h); draw(); return; }
    if (h.kind === 'boundary') startBoundaryDrag(h, e);
    else state.dragging = h;
  });
  window.addEventListener('mousemove', (e) => { if (state.dragging) dragTo(e); });
  // The drag's answers were float32: the release asks for the exact map.
  window.addEventListener('mouseup', () => {
    const moved = state.dragging && state.dragging.moved;
    state.dragging = null;
    if (moved) solve();
  });
}

// ---- constraints from the 3D view -------------------------------------------

// Barycentrics over GET /api/mesh's corners -> the file's corner order (what a constraint file means).
function fileBary(face, bary) {
  const reordered = state.mesh.file_triangles && state.mesh.file_triangles[face];
  if (!reordered) return bary;
  const tri = state.mesh.triangles.slice(3 * face, 3 * face + 3);
  return reordered.map((v) => bary[tri.indexOf(v)]);
}

function uvAt(face, bary) {
  const tri = state.mesh.triangles;
  let u = 0, v = 0;
  for (let k = 0; k < 3; k++) { u += bary[k] * state.uv[2 * tri[3 * face + k]]; v += bary[k] * state.uv[2 * tri[3 * face + k] + 1]; }
  return [u, v];
}

export function surfaceClick(e) {
  const mode = $('click3d').value;
  if (mode === 'orbit' || !state.uv) return;
  const hit = pick(e.clientX, e.clientY);
  if (!hit) return;
  const point = { face: hit.face, bary: fileBary(hit.face, hit.bary) }, uv = uvAt(hit.face, hit.bary);
  if (mode === 'point') {
    state.constraints.points.push({ ...point, uv });
    const added = state.constraints.points[state.constraints.points.length - 1];
    solve(e.timeStamp, () => { state.constraints.points = state.constraints.points.filter((p) => p !== added); draw(); });
  } else {
    (state.linePath = state.linePath || []).push({ ...point, uv });
    draw();
  }
}

export function finishLine() {
  const path = state.linePath;
  state.linePath = null;
  if (!path || path.length < 2) { setError('a line needs at least two surface points'); draw(); return; }
  const line = { path: path.map((p) => ({ face: p.face, bary: p.bary })), to: path.map((p) => p.uv) };
  state.constraints.lines.push(line);
  solve(null, () => { state.constraints.lines = state.constraints.lines.filter((l) => l !== line); draw(); });
}

export function clearConstraints() {
  state.constraints = { points: [], lines: [] };
  state.linePath = null;
  solve();
}
