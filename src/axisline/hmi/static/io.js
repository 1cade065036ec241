// I/O image: inputs (with forcing), outputs, sensors; refreshed.
"use strict";

const msg = document.getElementById("msg");

function rows(list, row) { return list.length ? list.map(row) : [el("tr", {}, el("td", { colspan: 4 }, "none"))]; }

function level(v) { return el("span", { class: "badge " + (v ? "ok" : "off") }, v ? "1" : "0"); }

async function force(name, value) {
  try {
    const r = await post("/api/write", { target: "io", name, value });
    say(msg, `${name}: ${r.old} -> ${r.new}`, true);
  } catch (e) { say(msg, e.message, false); }
}

async function refresh() {
  const io = await api("/api/io");
  document.querySelector("#inputs tbody").replaceChildren(...rows(io.inputs, i => el("tr", { "data-name": i.name },
    el("td", {}, i.name), el("td", {}, level(i.value)), el("td", {}, i.forced === null ? "" : `forced ${i.forced ? 1 : 0}`),
    el("td", {},
      el("button", { onclick: () => force(i.name, true) }, "1"), " ",
      el("button", { onclick: () => force(i.name, false) }, "0"), " ",
      el("button", { onclick: () => force(i.name, null) }, "release")))));
  document.querySelector("#outputs tbody").replaceChildren(...rows(io.outputs, o => el("tr", {},
    el("td", {}, o.name), el("td", {}, level(o.value)))));
  document.querySelector("#sensors tbody").replaceChildren(...rows(io.sensors, s => el("tr", {},
    el("td", {}, s.name), el("td", {}, level(s.value)))));
}

poll(refresh, 300, msg);
