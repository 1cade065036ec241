// Shared by every page: the nav bar, the JSON API, the write token, small DOM helpers.
"use strict";

const PAGES = [["/", "Overview"], ["/scope", "Scope"], ["/io", "I/O"], ["/device", "Device"], ["/events", "Events"]];
let INFO = { writes_allowed: false, token_header: null };

// el("td", {class: "num"}, "1.0") -> <td class="num">1.0</td>
function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k.startsWith("on")) e.addEventListener(k.slice(2), v);
    else if (v !== null && v !== undefined && v !== false) e.setAttribute(k, v === true ? "" : v);
  }
  for (const c of children.flat()) e.append(c instanceof Node ? c : String(c ?? ""));
  return e;
}

function fmt(x, digits = 3) {
  if (x === null || x === undefined) return "–";
  if (typeof x === "number") return Number.isInteger(x) ? String(x) : x.toFixed(digits);
  return String(x);
}

// the API answers {"error": "..."} with a status >= 400: thrown as an Error with that text
async function api(path, options) {
  const r = await fetch(path, options);
  const body = await r.json().catch(() => ({ error: `${r.status} ${r.statusText}` }));
  if (!r.ok) throw new Error(body.error || `${r.status} ${r.statusText}`);
  return body;
}

function token() { return sessionStorage.getItem("axisline-token") || ""; }

// writes and acknowledge carry the token the operator entered in the nav bar
function post(path, body) {
  const headers = { "Content-Type": "application/json" };
  if (token()) headers["X-Axisline-Token"] = token();
  return api(path, { method: "POST", headers, body: JSON.stringify(body ?? {}) });
}

function say(box, text, ok) {
  box.textContent = text;
  box.className = "msg " + (ok ? "info" : "error");
}

// repeat fn every ms, never two at once; errors shown in box
function poll(fn, ms, box) {
  const tick = async () => {
    try { await fn(); } catch (e) { if (box) say(box, e.message, false); }
    setTimeout(tick, ms);
  };
  tick();
}

function wsUrl(path) { return (location.protocol === "https:" ? "wss://" : "ws://") + location.host + path; }

async function setupNav() {
  const nav = el("nav", {}, el("span", { class: "brand" }, "axisline"));
  for (const [href, label] of PAGES)
    nav.append(el("a", { href, class: location.pathname === href ? "active" : null }, label));
  const right = el("span", { class: "right" });
  nav.append(right);
  document.body.prepend(nav);
  try { INFO = await api("/api/info"); } catch (e) { /* shown by the page's own requests */ }
  if (INFO.writes_allowed) {
    const input = el("input", { type: "password", id: "token", placeholder: "token (printed at start)", value: token() });
    input.addEventListener("input", () => sessionStorage.setItem("axisline-token", input.value.trim()));
    right.append("writes need the token:", input);
  } else {
    right.append(el("span", { class: "badge off", id: "readonly" }, "read-only"));
  }
}

document.addEventListener("DOMContentLoaded", setupNav);
