// Frame scheduling: everything is drawn in one requestAnimationFrame
// callback. A mouse event's stamp is closed on the frame after the one that
// drew its answer (that frame has then been handed to the compositor): the
// page's mouse-to-frame latency, kept in state.latencies.
import { $, state } from './state.js';
import { draw2d } from './view2d.js';
import { draw3d, uploadUV } from './view3d.js';
import { uploadLayout } from './layout_gl.js';

let frameRequested = false, uvDrawn = null, stamps = [];

export function draw(stamp = null) {
  if (stamp !== null) stamps.push(stamp);
  if (frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(() => {
    const t0 = performance.now();
    frameRequested = false;
    if (uvDrawn !== state.uv && state.uv) {
      // One float32 copy of a new answer feeds both views' vertex buffers.
      const uv32 = state.uv instanceof Float32Array ? state.uv : new Float32Array(state.uv);
      uploadUV(uv32);
      uploadLayout(uv32);
      uvDrawn = state.uv;
      state.uploadTimes.push(performance.now() - t0);
    }
    draw3d();
    draw2d();
    state.frames++;
    state.drawTimes.push(performance.now() - t0);
    const done = stamps;
    stamps = [];
    if (done.length) {
      requestAnimationFrame(() => {
        const now = performance.now();
        for (const t of done) state.latencies.push(now - t);
        $('frameMs').textContent = (now - done[done.length - 1]).toFixed(1);
      });
    }
  });
}
