// The noslip animation player (inlined into the page by sim/src/animation_page.rs): decodes
// the embedded frames and draws the balls, their spin marks and trails, the table and, for a
// one-ball table, the phase portrait with the contact in effect.
"use strict";
(function () {
  const errors = document.getElementById("errors");
  function fail(message) {
    errors.textContent += message + "\n";
    errors.hidden = false;
  }
  window.addEventListener("error", function (e) { fail(String(e.message)); });

  const D = JSON.parse(document.getElementById("noslip-data").textContent);
  const B = D.shown, F = D.frames, C = D.channels;
  const raw = atob(D.pos);
  const q = new Uint16Array(raw.length / 2);
  for (let i = 0; i < q.length; i++) {
    q[i] = raw.charCodeAt(2 * i) | (raw.charCodeAt(2 * i + 1) << 8);
  }
  const [vx0, vy0, vx1, vy1] = D.view;
  const un = function (v, lo, hi) { return lo + (hi - lo) * v / 65535; };
  const palette = ["#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"];
  const trailColours = ["#d62728", "#1f77b4", "#2ca02c", "#9467bd"];
  const TRAIL_FRAMES = 40;

  // Canvas coordinates of the balls' picture: the view fitted with a margin, y up.
  const canvas = document.getElementById("balls");
  const ctx = canvas.getContext("2d");
  const margin = 12;
  const scale = Math.min((canvas.width - 2 * margin) / (vx1 - vx0), (canvas.height - 2 * margin) / (vy1 - vy0));
  const X = function (x) { return margin + (x - vx0) * scale; };
  const Y = function (y) { return canvas.height - margin - (y - vy0) * scale; };

  function ball(f, b) {
    const o = (f * B + b) * C;
    return {
      x: un(q[o], vx0, vx1),
      y: un(q[o + 1], vy0, vy1),
      depth: C === 5 ? un(q[o + 2], D.depth[0], D.depth[1]) : 0,
      mx: un(q[o + C - 2], -1, 1),
      my: un(q[o + C - 1], -1, 1),
    };
  }

  function drawTable() {
    ctx.strokeStyle = "#444";
    ctx.lineWidth = 1;
    for (const s of D.segments) {
      ctx.beginPath();
      ctx.moveTo(X(s[0]), Y(s[1]));
      ctx.lineTo(X(s[2]), Y(s[3]));
      ctx.stroke();
    }
    ctx.fillStyle = "rgba(0,0,0,0.08)";
    for (const c of D.circles) {
      ctx.beginPath();
      ctx.arc(X(c[0]), Y(c[1]), Math.max(c[2] * scale, 1), 0, 2 * Math.PI);
      ctx.fill();
      ctx.stroke();
    }
  }

  // A trail: the frame positions of the last TRAIL_FRAMES frames and the contacts between
  // them; a jump of more than half the view (a periodic wrap) starts a new piece.
  function drawTrail(f, b) {
    const pts = [];
    for (let k = Math.max(0, f - TRAIL_FRAMES); k <= f; k++) {
      const t = D.trails[k][b] || [];
      if (k > Math.max(0, f - TRAIL_FRAMES)) {
        for (let i = 0; i + 1 < t.length; i += 2) {
          pts.push([un(t[i], vx0, vx1), un(t[i + 1], vy0, vy1)]);
        }
      }
      const p = ball(k, b);
      pts.push([p.x, p.y]);
    }
    ctx.strokeStyle = trailColours[b % trailColours.length];
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    for (let i = 0; i < pts.length; i++) {
      const jump = i > 0 && (Math.abs(pts[i][0] - pts[i - 1][0]) > (vx1 - vx0) / 2 ||
        Math.abs(pts[i][1] - pts[i - 1][1]) > (vy1 - vy0) / 2);
      if (i === 0 || jump) {
        ctx.moveTo(X(pts[i][0]), Y(pts[i][1]));
      } else {
        ctx.lineTo(X(pts[i][0]), Y(pts[i][1]));
      }
    }
    ctx.stroke();
  }

  function drawBalls(f) {
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    ctx.save();
    if (D.dim === 2) {
      ctx.beginPath();
      ctx.rect(X(vx0), Y(vy1), (vx1 - vx0) * scale, (vy1 - vy0) * scale);
      ctx.clip();
    }
    drawTable();
    const order = [];
    for (let b = 0; b < B; b++) {
      order.push(ball(f, b));
      order[b].b = b;
    }
    if (C === 5) {
      order.sort(function (a, c) { return c.depth - a.depth; });
    }
    for (const p of order) {
      const r = Math.max(D.radius[p.b] * scale, 1.5);
      ctx.beginPath();
      ctx.arc(X(p.x), Y(p.y), r, 0, 2 * Math.PI);
      ctx.fillStyle = palette[D.species[p.b] % palette.length];
      // In 3D the far balls are paler: a depth cue.
      ctx.globalAlpha = C === 5 ? 0.35 + 0.55 * (D.depth[1] - p.depth) / (D.depth[1] - D.depth[0] || 1) : 0.85;
      ctx.fill();
      ctx.globalAlpha = 1;
      ctx.strokeStyle = "#000";
      ctx.lineWidth = 1;
      ctx.stroke();
      // The spin mark: the body-fixed axis, from the centre towards the rim.
      ctx.beginPath();
      ctx.moveTo(X(p.x), Y(p.y));
      ctx.lineTo(X(p.x) + r * p.mx, Y(p.y) - r * p.my);
      ctx.strokeStyle = "#fff";
      ctx.lineWidth = Math.max(1, r / 5);
      ctx.stroke();
    }
    // Trails over the balls, so that none is hidden in a crowd.
    for (let b = 0; b < Math.min(B, D.trails.length ? D.trails[0].length : 0); b++) {
      drawTrail(f, b);
    }
    ctx.restore();
  }

  // The phase portrait of one body: its cloud (dark up to now, light after), the contact in
  // effect (red) and the few before it (orange).
  const pc = document.getElementById("portrait");
  const pctx = pc ? pc.getContext("2d") : null;
  const cloud = [];
  for (let i = 0; i + 3 < D.cloud.length; i += 4) {
    cloud.push({ t: D.cloud[i], body: D.cloud[i + 1], s: D.cloud[i + 2], y: D.cloud[i + 3] });
  }
  function mostContacts() {
    const counts = D.bodies.map(function () { return 0; });
    for (const p of cloud) { counts[p.body] += 1; }
    let best = 0;
    for (let k = 0; k < counts.length; k++) { if (counts[k] > counts[best]) { best = k; } }
    return best;
  }
  const ranges = D.bodies.map(function (_, k) {
    let lo = Infinity, hi = -Infinity;
    for (const p of cloud) { if (p.body === k) { lo = Math.min(lo, p.s); hi = Math.max(hi, p.s); } }
    for (const c of D.current) { if (c && c[0] === k) { lo = Math.min(lo, c[1]); hi = Math.max(hi, c[1]); } }
    if (!(hi > lo)) { lo -= 1; hi += 1; }
    return [lo, hi];
  });
  const yLo = D.dim === 2 ? -1 : 0;

  function drawPortrait(f) {
    if (!pctx) { return; }
    const W = pc.width, H = pc.height, L = 56, R = 12, T = 28, Bm = 44;
    pctx.clearRect(0, 0, W, H);
    const cur = D.current[f];
    const body = cur ? cur[0] : mostContacts();
    const [lo, hi] = ranges[body];
    const px = function (s) { return L + (s - lo) / (hi - lo) * (W - L - R); };
    const py = function (y) { return H - Bm - (y - yLo) / (1 - yLo) * (H - T - Bm); };
    pctx.strokeStyle = "#444";
    pctx.strokeRect(L, T, W - L - R, H - T - Bm);
    pctx.fillStyle = "#222";
    pctx.font = "12px sans-serif";
    pctx.fillText("Birkhoff coordinates, " + D.bodies[body].name, L, 16);
    pctx.fillText(D.bodies[body].x, L, H - 8);
    pctx.fillText(lo.toPrecision(3), L, H - Bm + 14);
    const hiText = hi.toPrecision(3);
    pctx.fillText(hiText, W - R - pctx.measureText(hiText).width, H - Bm + 14);
    pctx.fillText("1", L - 14, T + 10);
    pctx.fillText(String(yLo), L - 18, H - Bm);
    pctx.save();
    pctx.translate(14, H - Bm);
    pctx.rotate(-Math.PI / 2);
    pctx.fillText(D.bodies[body].y, 0, 0);
    pctx.restore();
    const now = D.t0 + f * D.dt;
    for (const p of cloud) {
      if (p.body !== body) { continue; }
      pctx.fillStyle = p.t <= now ? "rgba(31,119,180,0.8)" : "rgba(0,0,0,0.12)";
      pctx.fillRect(px(p.s) - 1, py(p.y) - 1, 2, 2);
    }
    for (let k = Math.max(0, f - 5); k <= f; k++) {
      const c = D.current[k];
      if (!c || c[0] !== body) { continue; }
      pctx.beginPath();
      pctx.arc(px(c[1]), py(c[2]), k === f ? 6 : 3.5, 0, 2 * Math.PI);
      pctx.fillStyle = k === f ? "#d62728" : "#ff7f0e";
      pctx.fill();
    }
  }

  const slider = document.getElementById("slider");
  const playButton = document.getElementById("play");
  const frameText = document.getElementById("frame");
  const timeText = document.getElementById("time");
  const contactsText = document.getElementById("contacts");
  let frame = 0;
  let playing = true;
  const hash = new URLSearchParams(window.location.hash.slice(1));
  if (hash.has("frame")) { frame = Math.min(F - 1, Math.max(0, parseInt(hash.get("frame"), 10) || 0)); }
  if (hash.has("pause")) { playing = false; }

  function show(f) {
    frame = f;
    drawBalls(f);
    drawPortrait(f);
    slider.value = String(f);
    frameText.textContent = String(f);
    timeText.textContent = "t = " + (D.t0 + f * D.dt).toPrecision(6);
    contactsText.textContent = D.contacts[f] + " contacts";
    playButton.textContent = playing ? "pause" : "play";
  }
  playButton.addEventListener("click", function () { playing = !playing; show(frame); });
  slider.addEventListener("input", function () { show(parseInt(slider.value, 10)); });
  document.getElementById("note").textContent =
    D.shown + " of " + D.balls + " balls in R^" + D.dim + (D.dim > 2 ? " (first three coordinates, oblique view)" : "") +
    "; " + F + " frames every " + D.dt.toPrecision(4) + " time units (each frame exact, from each ball's last contact)" +
    (D.t0 + (F - 1) * D.dt < D.end[0] - D.dt ? ", the beginning of a run of " + D.end[0].toPrecision(6) + " time units and " + D.end[1] + " contacts" : "") + "; " +
    "white mark: the body-fixed axis A e0, turning with the spin; trails: the first balls' last " + TRAIL_FRAMES +
    " frames with their contact points" + (pctx ? "; portrait: every " + "2^k-th contact, at most " + D.rules.cloud_points : "") + ".";
  show(frame);
  setInterval(function () {
    if (playing && F > 1) { show((frame + 1) % F); }
  }, 50);
})();
