// Overview: every axis (PLCopen state, position, velocity, following error, fault), refreshed.
"use strict";

const STATE_CLASS = { ErrorStop: "bad", Disabled: "off", Standstill: "ok", Stopping: "warn" };
const msg = document.getElementById("msg");

async function refresh() {
  const o = await api("/api/overview");
  document.getElementById("title").textContent = o.name || "Overview";
  document.getElementById("machine").textContent =
    `personality ${o.personality || "none"} · t = ${fmt(o.time, 3)} s · cycle ${o.cycle} · T = ${o.period_us} µs`;
  const rows = o.axes.map(a => el("tr", { "data-axis": a.name },
    el("td", {}, a.name),
    el("td", {}, el("span", { class: "badge " + (STATE_CLASS[a.state] || "ok"), "data-state": a.state }, a.state)),
    el("td", { class: "num" }, fmt(a.position, 4)),
    el("td", { class: "num" }, fmt(a.velocity, 3)),
    el("td", { class: "num" }, fmt(a.following_error, 5)),
    el("td", {}, a.unit),
    el("td", {}, a.error_id ? `${a.error_id}: ${a.error}` : (a.warning || ""))));
  document.querySelector("#axes tbody").replaceChildren(...rows);
  const faults = o.faults.concat(o.job.failed ? [`job: ${o.job.failed}`] : []);
  document.getElementById("faults").replaceChildren(...(faults.length ? faults : ["none"]).map(f => el("li", {}, f)));
}

document.getElementById("ack").addEventListener("click", async () => {
  try {
    const r = await post("/api/acknowledge");
    const what = r.axes.map(a => `axis ${a.axis}`).concat(r.device ? [r.device] : []);
    say(msg, "acknowledged: " + (what.join(", ") || "no active fault"), true);
  } catch (e) { say(msg, e.message, false); }
});

poll(refresh, 300, msg);
