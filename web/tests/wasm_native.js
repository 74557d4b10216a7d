// The core in WebAssembly gives the same runs as the native command line: the shipped examples and
// a few hundred random machines give the same events JSON byte for byte (every event, time, state
// and energy: the two builds compute with one maths library, cmake/maths.cmake), and bad input is
// refused with the same one-line message.
//   node wasm_native.js WHATNEXT_JS WHATNEXT_CLI SOURCE_DIR [COUNT]
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { spawnSync } = require('child_process');

const [modulePath, cli, sourceDir, countArg] = process.argv.slice(2);
const count = Number(countArg || 300);

// A small deterministic generator (mulberry32), so that a failure can be reproduced.
function generator(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// Machines around the paper's: each key is varied with some probability, over ranges that give
// mostly valid machines and a share of refused ones.
function randomSets(rand) {
  const pick = (list) => list[Math.floor(rand() * list.length)];
  const num = (lo, hi) => Number((lo + (hi - lo) * rand()).toPrecision(6));
  const sets = [];
  const maybe = (p, key, value) => { if (rand() < p) sets.push(`${key}=${value()}`); };
  maybe(0.6, 'geometry.rope_length', () => num(0.55, 1.3));
  maybe(0.4, 'geometry.seesaw_right_arm', () => num(0.35, 0.85));
  maybe(0.3, 'geometry.lid_half_length', () => num(0.1, 0.3));
  maybe(0.3, 'geometry.hinge_distance', () => num(0.6, 1.0));
  maybe(0.3, 'geometry.hinge_angle', () => num(5, 40));
  maybe(0.4, 'masses.sandbag', () => num(0.1, 3));
  maybe(0.4, 'masses.lid', () => num(0.05, 1.5));
  maybe(0.4, 'start.sandbag_x', () => num(-0.7, -0.05));
  maybe(0.4, 'start.sandbag_height', () => num(0.2, 2));
  maybe(0.3, 'start.seesaw_angle', () => num(-40, 10));
  maybe(0.3, 'start.lid_angle', () => num(0, 20));
  maybe(0.5, 'run.impact_law', () => pick(['rope', 'angular-momentum-sum', 'kinetic-energy', 'linear-momentum']));
  maybe(0.2, 'balloon.model', () => pick(['program', 'lagrangian', 'added-mass']));
  maybe(0.1, 'damping.pivot', () => num(0, 0.5));
  maybe(0.1, 'damping.lid_hinge', () => num(0, 0.1));
  maybe(0.1, 'balloon.drag_coefficient', () => num(0.1, 1));
  if (rand() < 0.1) sets.push('radio.enabled=true');
  if (rand() < 0.1) {
    sets.push(`seesaw.left_arm=${num(0.5, 2)}`);
    if (rand() < 0.5) sets.push(`seesaw.mass=${num(0.05, 1)}`);
  }
  if (rand() < 0.1) {
    sets.push(`run.integrator=${pick(['euler', 'rk4'])}`);
    sets.push(`run.step=${pick([1e-3, 5e-4])}`);
  }
  sets.push('run.t_max=3');
  return sets;
}

function runCli(args, dir) {
  const out = path.join(dir, 'events.json');
  fs.rmSync(out, { force: true });
  const p = spawnSync(cli, ['run', ...args, '--events', out, '-q'], { cwd: sourceDir, encoding: 'utf8' });
  if (p.status === 0) return { ok: true, text: fs.readFileSync(out, 'utf8') };
  return { ok: false, status: p.status, message: p.stderr.trim() };
}

async function main() {
  const createWhatnext = require(path.resolve(modulePath));
  const wasm = await createWhatnext();
  const presets = wasm.presets();
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-wasm-'));
  const failures = [];
  let same = 0, refused = 0, events = 0;

  const check = (name, preset, sets) => {
    const input = { toml: preset.toml, source: preset.source, label: preset.label, sets };
    const cliArgs = (more) => [...preset.cli.split(' '), ...[...sets, ...more].flatMap((s) => ['--set', s])];
    const mine = wasm.events(input);
    const theirs = runCli(cliArgs([]), dir);
    const what = `${name}: whatnext run ${cliArgs([]).join(' ')}`;
    if (!mine.ok || !theirs.ok) {
      if (mine.ok || theirs.ok) {
        failures.push(`${what}: WebAssembly ${mine.ok ? 'runs' : 'refuses (' + mine.message + ')'}, ` +
                      `the CLI ${theirs.ok ? 'runs' : 'refuses (' + theirs.message + ')'}`);
      } else if (theirs.status !== 2 || theirs.message !== `whatnext: error: ${mine.message}`) {
        failures.push(`${what}: messages differ:\n  wasm: ${mine.message}\n  cli:  ${theirs.message} (exit ${theirs.status})`);
      } else {
        ++refused;
      }
      return;
    }
    events += JSON.parse(theirs.text).events.length;
    if (mine.text === theirs.text) {
      ++same;
      return;
    }
    const a = mine.text.split('\n'), b = theirs.text.split('\n');
    const k = b.findIndex((line, j) => line !== a[j]);
    const i = k < 0 ? b.length : k;  // or WebAssembly's has lines more
    failures.push(`${what}: the events JSON differs at line ${i + 1}: '${a[i]}' here, '${b[i]}' from the CLI`);
  };

  for (const preset of presets) check(preset.id, preset, []);
  const rand = generator(20240610);
  for (let i = 0; i < count; ++i) check(`machine ${i}`, presets[i % 2], randomSets(rand));
  fs.rmSync(dir, { recursive: true, force: true });

  const total = presets.length + count;
  console.log(`${presets.length} shipped and ${count} random machines: ${same} with the same events JSON byte ` +
              `for byte, ${refused} refused with the same message (${events} events compared)`);
  // The comparison means something only if most machines run and some are refused.
  if (same < total / 2) failures.push(`only ${same} machines ran`);
  if (refused === 0) failures.push('no machine was refused: the messages were not compared');
  for (const f of failures.slice(0, 20)) console.error(`FAIL ${f}`);
  if (failures.length) {
    console.error(`${failures.length} failures`);
    process.exit(1);
  }
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
