// One of the map's Web Workers (map.js starts one per core): the library's sweep in WebAssembly
// (web/wasm/map.cpp). The page sends {start: {input, vary}} once per map, then {block: [from, to]}
// for each stretch of machines; each block comes back as one Float64Array of numbers (handed over,
// not copied) and the CSV rows of `whatnext sweep`, never as an object per machine. It also makes
// the phase plots' table of a run ({phase: {input, maxRows}}), off the page's thread.
// Served, the module is whatnext.js next to this file; in the single-file page both come inlined
// in one blob, createWhatnext already defined.
'use strict';
if (typeof createWhatnext === 'undefined') importScripts('whatnext.js');

const ready = createWhatnext().then((wasm) => {
  self.postMessage({ hello: { columns: wasm.phaseColumns() } });
  return wasm;
});

self.onmessage = async (e) => {
  const wasm = await ready;
  const d = e.data;
  let reply;
  try {
    if (d.start) reply = { map: d.map, started: wasm.mapStart(d.start.input, d.start.vary) };
    else if (d.block) {
      const t0 = performance.now();
      const r = wasm.mapBlock(d.block[0], d.block[1]);
      reply = { map: d.map, block: d.block, result: r, ms: performance.now() - t0 };
    } else if (d.phase) reply = { phase: d.id, result: wasm.phaseTable(d.phase.input, d.phase.maxRows) };
  } catch (err) {  // a wasm abort or out of memory: one message, not a dead map
    const result = { ok: false, kind: 'error', message: `the WebAssembly module failed (${err.message || err})` };
    reply = d.phase ? { phase: d.id, result } : { map: d.map, block: d.block, started: d.start ? result : undefined, result };
  }
  const buffers = [];
  if (reply.result && reply.result.numbers) buffers.push(reply.result.numbers.buffer);
  if (reply.result && reply.result.data) for (const c of reply.result.data) buffers.push(c.buffer);
  self.postMessage(reply, buffers);
};
