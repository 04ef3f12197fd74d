// The 2D view: the layout's triangles (optionally coloured by per-triangle
// angle or area distortion, with a colour bar) and flipped triangles in red,
// drawn with WebGL by layout_gl.js on the canvas below; on the 2D canvas above
// it the boundary and the handles the mouse can take: boundary vertices
// (fixed boundary; a selected range highlighted), pins (natural map) and
// constraint targets (points, and the path points of lines).
import { $, loopIndex, natural, state } from './state.js';
import { colourOf, faceDistortion } from './distortion.js';
import { BINS, VMAX, drawLayout } from './layout_gl.js';
import { resize } from './view3d.js';

// The layout window: [-0.15, 1.15]^2 (maps come out in [0, 1]^2), fixed so a
// dragged vertex stays under the mouse.
export function view2d() {
  const c = $('view2d'), w = c.clientWidth, h = c.clientHeight;
  const side = Math.min(w, h) / 1.3;
  return { ox: (w - 1.3 * side) / 2 + 0.15 * side, oy: (h + 1.3 * side) / 2 - 0.15 * side, side };
}
export const toScreen = (v, u, w) => [v.ox + u * v.side, v.oy - w * v.side];
export const toUV = (v, x, y) => [(x - v.ox) / v.side, (v.oy - y) / v.side];

// Draggable things in page pixels, constraint targets first (they win ties).
export function handles() {
  if (!state.uv) return [];
  const v = view2d(), rect = $('view2d').getBoundingClientRect();
  const at = (u, w) => { const [x, y] = toScreen(v, u, w); return { x: rect.left + window.scrollX + x, y: rect.top + window.scrollY + y }; };
  const list = [];
  state.constraints.points.forEach((p, index) => list.push({ kind: 'point', index, ...at(p.uv[0], p.uv[1]) }));
  state.constraints.lines.forEach((l, index) => l.to.forEach((t, k) => list.push({ kind: 'line', index, k, ...at(t[0], t[1]) })));
  if (natural()) {
    for (const p of state.pins || []) list.push({ kind: 'pin', vertex: p[0], ...at(state.uv[2 * p[0]], state.uv[2 * p[0] + 1]) });
  } else {
    for (const i of state.mesh.boundary_loops[0]) list.push({ kind: 'boundary', vertex: i, ...at(state.uv[2 * i], state.uv[2 * i + 1]) });
  }
  return list;
}

export function draw2d() {
  const c = $('view2d');
  resize(c);
  // willReadFrequently: a CPU canvas (a few hundred handles and the boundary;
  // the GPU raster of headless Chromium is SwiftShader, slower here).
  const ctx = c.getContext('2d', { willReadFrequently: true }), dpr = window.devicePixelRatio || 1, v = view2d();
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, c.clientWidth, c.clientHeight);
  const colour = $('colour').value;
  const values = colour === 'none' || !state.uv ? null : faceDistortion(state.mesh, state.uv, colour);
  drawLayout(v, colour, values);
  if (!state.uv) return;
  ctx.lineWidth = 1.5;
  ctx.strokeStyle = '#222';
  for (const loop of state.mesh.boundary_loops) {
    ctx.beginPath();
    loop.forEach((i, k) => { const p = toScreen(v, state.uv[2 * i], state.uv[2 * i + 1]); k ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]); });
    ctx.closePath();
    ctx.stroke();
  }
  drawHandles(ctx, v);
  drawConstraints(ctx, v);
  if (colour !== 'none') colourBar(ctx, c.clientWidth, colour);
  if (state.preview) {
    ctx.fillStyle = '#7a3e00';
    ctx.font = '13px system-ui, sans-serif';
    ctx.fillText(state.preview.label, 10, c.clientHeight - 10);
  }
}

function colourBar(ctx, width, colour) {
  const x = width - 40, y = 30, h = 160, vmax = VMAX[colour];
  for (let k = 0; k < BINS; k++) {
    ctx.fillStyle = colourOf((k + 0.5) / BINS);
    ctx.fillRect(x, y + h - (k + 1) * h / BINS, 14, h / BINS + 0.5);
  }
  ctx.strokeStyle = '#444';
  ctx.strokeRect(x, y, 14, h);
  ctx.fillStyle = '#222';
  ctx.font = '11px system-ui, sans-serif';
  ctx.textAlign = 'right';
  ctx.fillText(`≥${vmax}`, x - 3, y + 8);
  ctx.fillText(Math.sqrt(vmax).toFixed(2), x - 3, y + h / 2 + 4);
  ctx.fillText('1', x - 3, y + h);
  ctx.fillText(colour, x + 14, y - 8);
  ctx.textAlign = 'left';
}

function drawHandles(ctx, v) {
  const dot = (i, colour, r) => {
    const p = toScreen(v, state.uv[2 * i], state.uv[2 * i + 1]);
    ctx.fillStyle = colour;
    ctx.beginPath();
    ctx.arc(p[0], p[1], r, 0, 2 * Math.PI);
    ctx.fill();
  };
  if (natural()) {
    for (const p of state.pins || []) dot(p[0], '#e07000', 6);
    return;
  }
  const index = loopIndex(), sel = state.selection, n = state.mesh.boundary_loops[0].length;
  for (const i of state.mesh.boundary_loops[0]) {
    const selected = sel && (index[i] - sel.from + n) % n <= (sel.to - sel.from + n) % n;
    const moved = state.moves.has(i);
    dot(i, selected ? '#0a9a50' : moved ? '#e07000' : '#1f5fbf', selected ? 4 : moved ? 4 : 2);
  }
}

function drawConstraints(ctx, v) {
  const mark = (u, w, colour) => {
    const [x, y] = toScreen(v, u, w);
    ctx.strokeStyle = colour;
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(x - 6, y); ctx.lineTo(x + 6, y); ctx.moveTo(x, y - 6); ctx.lineTo(x, y + 6);
    ctx.stroke();
    ctx.beginPath();
    ctx.arc(x, y, 5, 0, 2 * Math.PI);
    ctx.stroke();
  };
  for (const p of state.constraints.points) mark(p.uv[0], p.uv[1], '#8a00c2');
  for (const l of state.constraints.lines) {
    ctx.strokeStyle = '#8a00c2';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    l.to.forEach((t, k) => { const [x, y] = toScreen(v, t[0], t[1]); k ? ctx.lineTo(x, y) : ctx.moveTo(x, y); });
    ctx.stroke();
    for (const t of l.to) mark(t[0], t[1], '#8a00c2');
  }
  for (const p of state.linePath || []) mark(p.uv[0], p.uv[1], '#c28a00');
}
