// Device view: the personality's sections rendered generically (axisline.hmi.devices):
// parameters (editable, range shown, validated), table, bits, plot, diagnostics, text.
"use strict";

const msg = document.getElementById("msg");
const RENDER = { parameters, table, bits, plot, diagnostics, text };

async function write(row, input) {
  try {
    const value = input.type === "number" ? Number(input.value) : input.value;
    if (input.type === "number" && (input.value.trim() === "" || !Number.isFinite(value))) throw new Error(`${row.name}: a number is expected`);
    const r = await post("/api/write", { target: "device", name: row.name, value });
    input.classList.remove("invalid");
    say(msg, `${row.label || row.name}: ${fmt(r.old)} -> ${fmt(r.new)}`, true);
    input.blur();
    refresh();
  } catch (e) { input.classList.add("invalid"); say(msg, e.message, false); }
}

function parameters(s) {
  const range = r => (r.min ?? r.max) === undefined || (r.min === null && r.max === null) ? "" : `${fmt(r.min)} … ${fmt(r.max)}`;
  return el("table", {}, el("tr", {}, ["parameter", "value", "unit", "range", ""].map(h => el("th", {}, h))),
    s.rows.map(r => {
      let edit = "";
      if (r.writable) {
        const numeric = typeof r.value === "number";
        const input = el("input", { type: numeric ? "number" : "text", value: r.value ?? "", min: r.min, max: r.max, step: "any", "data-name": r.name, size: 10 });
        input.addEventListener("keydown", e => { if (e.key === "Enter") write(r, input); });
        edit = el("span", {}, input, " ", el("button", { onclick: () => write(r, input) }, "Write"));
      }
      return el("tr", { "data-name": r.name }, el("td", { title: r.name }, r.label || r.name),
        el("td", { class: "num" }, fmt(r.value)), el("td", {}, r.unit || ""), el("td", {}, range(r)), el("td", {}, edit));
    }));
}

function table(s) {
  return el("table", {}, el("tr", {}, s.columns.map(c => el("th", {}, c))),
    s.rows.map(row => el("tr", {}, row.map(v => el("td", { class: typeof v === "number" ? "num" : null }, fmt(v))))));
}

function bits(s) {
  return el("table", {}, s.words.map(w => el("tr", {},
    el("td", {}, w.name), el("td", { class: "num" }, typeof w.value === "number" ? "0x" + w.value.toString(16).toUpperCase() : fmt(w.value)),
    el("td", { class: "bits" }, w.bits.map(b => el("span", { class: b.set ? "set" : null, title: `bit ${b.bit}` }, b.name))))));
}

function diagnostics(s) {
  const active = s.rows.filter(r => r.active).length;
  return el("div", {},
    el("table", {}, el("tr", {}, ["code", "diagnosis", "state"].map(h => el("th", {}, h))),
      s.rows.map(r => el("tr", {}, el("td", {}, r.code), el("td", {}, r.text),
        el("td", {}, el("span", { class: "badge " + (r.active ? "bad" : "ok") }, r.active ? "active" : "–"))))),
    el("button", { onclick: acknowledge }, `Acknowledge${active ? ` (${active} active)` : ""}`));
}

function text(s) { return el("pre", {}, s.lines.join("\n")); }

function plot(s) {
  const c = el("canvas", { width: 700, height: 260 }), g = c.getContext("2d");
  const xs = s.series.flatMap(a => a.x), ys = s.series.flatMap(a => a.y).filter(v => v !== null);
  if (!xs.length) return el("p", {}, "no data");
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const X = x => 50 + (x - x0) / ((x1 - x0) || 1) * 640, Y = y => 240 - (y - y0) / ((y1 - y0) || 1) * 225;
  g.font = "12px system-ui"; g.fillStyle = "#444";
  g.fillText(fmt(y1), 2, 16); g.fillText(fmt(y0), 2, 240); g.fillText(fmt(x0), 50, 256); g.fillText(fmt(x1), 650, 256);
  g.fillText(`${s.x_label || ""} / ${s.y_label || ""}`, 300, 256);
  s.series.forEach((a, k) => {
    g.strokeStyle = ["#1f5fbf", "#c0392b", "#1e8449", "#8e44ad"][k % 4]; g.beginPath();
    a.x.forEach((x, i) => { if (a.y[i] !== null) i ? g.lineTo(X(x), Y(a.y[i])) : g.moveTo(X(x), Y(a.y[i])); });
    g.stroke(); g.fillStyle = g.strokeStyle; g.fillText(a.name, 60 + 120 * k, 14);
  });
  return c;
}

async function acknowledge() {
  try { const r = await post("/api/acknowledge"); say(msg, "acknowledged" + (r.device ? ": " + r.device : ""), true); refresh(); }
  catch (e) { say(msg, e.message, false); }
}

async function refresh() {
  if (document.activeElement && document.activeElement.tagName === "INPUT") return;  // the operator is typing
  const v = await api("/api/device");
  document.getElementById("title").textContent = v.title || "Device";
  const out = v.sections.map(s => el("section", { "data-type": s.type }, el("h2", {}, s.title || s.type),
    RENDER[s.type] ? RENDER[s.type](s) : el("p", {}, `(section type ${s.type})`)));
  document.getElementById("sections").replaceChildren(...(out.length ? out : [el("p", {}, "this machine shows no device view")]));
}

poll(refresh, 1000, msg);
