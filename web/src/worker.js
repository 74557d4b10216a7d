// The library runs here, in a Web Worker, so that a long run never freezes the page: the page
// sends {id, fn, input} and gets {id, result} back; while a run is under way the worker posts
// {progress: t} now and then, and the page stops a run by ending the worker.
// Served, the module is whatnext.js next to this file; in the single-file page (whatnext.html)
// both come inlined in one blob, createWhatnext already defined.
'use strict';
if (typeof createWhatnext === 'undefined') importScripts('whatnext.js');

// Fixed-step runs take t_max / step steps whatever the machine does. More than this many and the
// page asks before starting (about two seconds of work in Chromium on a slow machine).
const kStepBudget = 2e6;

let last = 0;
self.whatnextProgress = (t) => {  // called by the bindings' sample observer
  const now = Date.now();
  if (now - last < 150) return;
  last = now;
  self.postMessage({ progress: t });
};

const ready = createWhatnext().then((wasm) => {
  self.postMessage({ hello: { presets: wasm.presets(), keys: wasm.keys(), names: wasm.names() } });
  return wasm;
});

function answer(wasm, fn, input) {
  if (fn === 'run' && !input.force) {
    const plan = wasm.plan(input);
    if (!plan.ok) return plan;
    const steps = plan.t_max / plan.step;
    if (plan.integrator !== 'adaptive' && steps > kStepBudget) {
      return { ok: false, kind: 'budget', steps, integrator: plan.integrator, t_max: plan.t_max, step: plan.step };
    }
  }
  if (fn === 'timeRun') {  // milliseconds for `repeat` runs of one input (web/tests/page.js speed)
    const times = [];
    for (let i = 0; i < input.repeat; ++i) {
      const t0 = performance.now();
      wasm.run(input.input);
      times.push(performance.now() - t0);
    }
    return times.sort((a, b) => a - b);
  }
  if (fn === 'validity') {  // which slider positions the library accepts: {key: [true|false, ...]}
    const out = {};
    for (const { key, values } of input.probes) {
      out[key] = values.map((v) => wasm.plan({ ...input.input, sets: [...input.input.sets, `${key}=${v}`] }).ok);
    }
    return out;
  }
  if (!['run', 'toml', 'events', 'csv'].includes(fn)) return { ok: false, kind: 'error', message: `no function ${fn}` };
  return wasm[fn](input);
}

self.onmessage = async (e) => {
  const { id, fn, input } = e.data;
  const wasm = await ready;
  let result;
  try {
    last = Date.now();
    result = answer(wasm, fn, input);
  } catch (err) {  // a wasm abort or out of memory: one message, not a dead page
    result = { ok: false, kind: 'error', message: `the WebAssembly module failed (${err.message || err})` };
  }
  // The sample columns are handed over, not copied.
  const buffers = result && result.samples ? Object.values(result.samples).filter((c) => c instanceof Float64Array).map((c) => c.buffer) : [];
  self.postMessage({ id, result }, buffers);
};
