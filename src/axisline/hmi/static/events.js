// Event log, live over a WebSocket: newest first.
"use strict";

const msg = document.getElementById("msg");
const body = document.querySelector("#events tbody");
let last = 0;

function when(t) {
  if (typeof t === "number") return new Date(t * 1000).toISOString().slice(11, 23);
  return typeof t === "string" ? t.slice(11, 23) : "";  // ISO 8601 UTC: the time of day
}

function connect() {
  const ws = new WebSocket(wsUrl(`/ws/events?after=${last}`));
  ws.onopen = () => say(msg, "live", true);
  ws.onmessage = ev => {
    for (const e of JSON.parse(ev.data).events) {
      last = Math.max(last, e.seq);
      body.prepend(el("tr", { class: e.accepted === false ? "bad" : null, "data-kind": e.kind },
        el("td", { class: "num" }, e.seq), el("td", {}, when(e.time)), el("td", {}, e.kind), el("td", {}, e.message)));
    }
    while (body.rows.length > 1000) body.deleteRow(-1);
  };
  ws.onclose = () => { say(msg, "connection lost; reconnecting …", false); setTimeout(connect, 1000); };
}

connect();
