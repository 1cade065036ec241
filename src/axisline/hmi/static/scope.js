// Live scope: any trace channel, one lane each, rolling window; pause, zoom, pan, CSV export.
// Samples arrive over /ws/scope as blocks {since, next, skipped, t: [...], data: {ch: [...]}}.
"use strict";

const MAX_HELD = 200000;        // samples kept per channel in the page
const COLORS = ["#1f5fbf", "#c0392b", "#1e8449", "#8e44ad", "#d35400", "#117a8b", "#7d6608", "#555"];
const msg = document.getElementById("msg");
const canvas = document.getElementById("plot");
const ctx = canvas.getContext("2d");
let meta = {};                  // channel -> {unit, kind}
let period = 0.001;             // s between samples
let selected = [];
let held = { t: [], data: {} };
let received = 0, skipped = 0;
let windowS = 5, paused = false, end = null;   // end: right edge (s) while paused
let ws = null;

function reset() {
  held = { t: [], data: Object.fromEntries(selected.map(c => [c, []])) };
  received = 0; skipped = 0;
}

function ask() {
  reset();
  localStorage.setItem("axisline-scope", JSON.stringify(selected));
  if (ws && ws.readyState === WebSocket.OPEN)
    ws.send(JSON.stringify({ channels: selected, since: null, limit: Math.min(5000, Math.ceil(windowS / period)) }));
}

function take(block) {
  if (block.error) { say(msg, block.error, false); return; }
  if (selected.some(c => !(c in block.data))) return;  // a block for the previous choice
  for (const v of block.t) held.t.push(v);
  for (const c of selected) for (const v of block.data[c] || []) held.data[c].push(v);
  received += block.t.length; skipped += block.skipped;
  const extra = held.t.length - MAX_HELD;
  if (extra > 0) { held.t.splice(0, extra); for (const c of selected) held.data[c].splice(0, extra); }
  document.getElementById("status").textContent =
    `${received} samples received` + (skipped ? `, ${skipped} skipped` : "") + (held.t.length ? `, t = ${fmt(held.t[held.t.length - 1], 3)} s` : "");
  canvas.dataset.samples = received;
}

function connect() {
  ws = new WebSocket(wsUrl("/ws/scope"));
  ws.onopen = () => { say(msg, "", true); ask(); };
  ws.onmessage = ev => take(JSON.parse(ev.data));
  ws.onclose = () => { say(msg, "connection lost; reconnecting …", false); setTimeout(connect, 1000); };
}

// first index with t >= x (held.t is ascending)
function lowerBound(x) {
  let lo = 0, hi = held.t.length;
  while (lo < hi) { const mid = (lo + hi) >> 1; if (held.t[mid] < x) lo = mid + 1; else hi = mid; }
  return lo;
}

function draw() {
  const W = canvas.width, H = canvas.height, left = 70, bottom = 22;
  ctx.clearRect(0, 0, W, H);
  ctx.font = "12px system-ui";
  const n = held.t.length;
  const right = paused && end !== null ? end : (n ? held.t[n - 1] : 0);
  const t0 = right - windowS;
  const i0 = lowerBound(t0), i1 = lowerBound(right + 1e-9);
  const lanes = Math.max(1, selected.length), laneH = (H - bottom) / lanes;
  const x = t => left + (t - t0) / windowS * (W - left - 4);
  selected.forEach((c, k) => {
    const ys = held.data[c] || [], top = k * laneH;
    let lo = Infinity, hi = -Infinity;
    for (let i = i0; i < i1; i++) { const v = ys[i]; if (v !== null) { if (v < lo) lo = v; if (v > hi) hi = v; } }
    if (meta[c]?.kind === "bool") { lo = 0; hi = 1; }
    if (!isFinite(lo)) { lo = -1; hi = 1; }
    if (hi - lo < 1e-12) { lo -= 0.5; hi += 0.5; }
    const pad = (hi - lo) * 0.08, y = v => top + 4 + (1 - (v - lo + pad) / (hi - lo + 2 * pad)) * (laneH - 8);
    ctx.strokeStyle = "#ddd"; ctx.beginPath(); ctx.moveTo(left, top + laneH); ctx.lineTo(W, top + laneH); ctx.stroke();
    ctx.fillStyle = "#666"; ctx.fillText(fmt(hi, 3), 4, top + 14); ctx.fillText(fmt(lo, 3), 4, top + laneH - 4);
    ctx.strokeStyle = COLORS[k % COLORS.length]; ctx.lineWidth = 1.5; ctx.beginPath();
    const step = Math.max(1, Math.floor((i1 - i0) / (W - left)));  // at most a point per pixel
    let pen = false;
    for (let i = i0; i < i1; i += step) {
      const v = ys[i];
      if (v === null) { pen = false; continue; }
      pen ? ctx.lineTo(x(held.t[i]), y(v)) : ctx.moveTo(x(held.t[i]), y(v)); pen = true;
    }
    ctx.stroke();
    const last = i1 > i0 ? ys[i1 - 1] : null, unit = meta[c]?.unit;
    ctx.fillStyle = COLORS[k % COLORS.length];
    ctx.fillText(`${c}${unit ? " [" + unit + "]" : ""} = ${fmt(last, 4)}`, left + 8, top + 14);
  });
  // time axis: about 8 ticks at 1, 2 or 5 x 10^n s
  ctx.fillStyle = "#444"; ctx.strokeStyle = "#bbb"; ctx.lineWidth = 1;
  const raw = windowS / 8, p = 10 ** Math.floor(Math.log10(raw)), tick = [1, 2, 5, 10].map(m => m * p).find(s => s >= raw);
  for (let t = Math.ceil(t0 / tick) * tick; t <= right; t += tick) {
    ctx.beginPath(); ctx.moveTo(x(t), H - bottom); ctx.lineTo(x(t), H - bottom + 4); ctx.stroke();
    ctx.fillText(fmt(t, tick < 1 ? 2 : 0) + " s", x(t) - 14, H - 6);
  }
}

function frame() { if (!paused) draw(); requestAnimationFrame(frame); }

function zoom(factor) {
  windowS = Math.min(600, Math.max(10 * period, windowS * factor));
  canvas.dataset.window = windowS;
  draw();
}

function exportCsv() {
  const header = ["t[s]"].concat(selected.map(c => meta[c]?.unit ? `${c}[${meta[c].unit}]` : c));
  const lines = [header.join(",")];
  for (let i = 0; i < held.t.length; i++)
    lines.push([held.t[i]].concat(selected.map(c => held.data[c][i] ?? "")).join(","));
  const a = el("a", { href: URL.createObjectURL(new Blob([lines.join("\n") + "\n"], { type: "text/csv" })), download: "scope.csv" });
  document.body.append(a); a.click(); a.remove();
}

async function init() {
  const ch = await api("/api/channels");
  period = ch.period_s || 0.001;
  meta = Object.fromEntries(ch.channels.map(c => [c.name, c]));
  const saved = JSON.parse(localStorage.getItem("axisline-scope") || "null");
  selected = (saved || ch.channels.slice(0, 2).map(c => c.name)).filter(c => c in meta);
  const box = document.getElementById("channels");
  if (!ch.channels.length) box.textContent = "this machine records no trace";
  for (const c of ch.channels) {
    const input = el("input", { type: "checkbox", value: c.name, checked: selected.includes(c.name) });
    input.addEventListener("change", () => {
      selected = ch.channels.map(x => x.name).filter(n => n === c.name ? input.checked : selected.includes(n));
      ask();
    });
    box.append(el("label", {}, input, ` ${c.name}`, c.unit ? ` [${c.unit}]` : ""));
  }
  document.getElementById("window").addEventListener("change", e => { windowS = Number(e.target.value); zoom(1); });
  document.getElementById("pause").addEventListener("click", e => {
    paused = !paused;
    end = paused && held.t.length ? held.t[held.t.length - 1] : null;
    e.target.textContent = paused ? "Run" : "Pause";
  });
  document.getElementById("zoomin").addEventListener("click", () => zoom(0.5));
  document.getElementById("zoomout").addEventListener("click", () => zoom(2));
  document.getElementById("csv").addEventListener("click", exportCsv);
  canvas.addEventListener("wheel", e => { e.preventDefault(); zoom(e.deltaY > 0 ? 1.25 : 0.8); });
  let drag = null;  // paused: drag the plot sideways to pan
  canvas.addEventListener("mousedown", e => { if (paused) drag = { x: e.clientX, end }; });
  window.addEventListener("mouseup", () => { drag = null; });
  canvas.addEventListener("mousemove", e => {
    if (!drag) return;
    end = drag.end - (e.clientX - drag.x) / (canvas.width - 74) * windowS;
    draw();
  });
  connect();
  requestAnimationFrame(frame);
}

init().catch(e => say(msg, e.message, false));
