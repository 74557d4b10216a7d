// The parameter panel: a field for every input key the library knows (its own list, units and
// help), grouped, with sliders for the numbers. A change is handed on as the text of a
// `--set KEY=VALUE`, so that the page's machine and messages are the command line's.
(function () {
  'use strict';
  const S = window.whatnextStrings;

  const kGroups = [
    { title: 'Geometry', match: (k) => k.startsWith('geometry.') },
    { title: 'Masses', match: (k) => k.startsWith('masses.') },
    { title: 'Air and balloon', match: (k) => k.startsWith('air.') || k === 'balloon.radius' || k === 'balloon.model' },
    { title: 'Start', match: (k) => k.startsWith('start.') },
    { title: 'Run: integrator and impact law', match: (k) => k.startsWith('run.') },
    { title: 'Extensions beyond the paper', match: () => true, closed: true },
  ];

  // Slider ranges in the input's units (log: a logarithmic slider).
  const kRanges = {
    'geometry.seesaw_right_arm': [0.2, 1.2], 'geometry.lid_half_length': [0.05, 0.5],
    'geometry.rope_length': [0.3, 2], 'geometry.hinge_distance': [0.3, 1.5], 'geometry.hinge_angle': [-30, 60],
    'geometry.rope_on_lid': [0.02, 1],
    'masses.sandbag': [0.05, 5, 'log'], 'masses.lid': [0.05, 5, 'log'],
    'air.density': [0.5, 2], 'air.helium_density': [0.05, 1.2], 'balloon.radius': [0.05, 0.5],
    'balloon.rubber_mass': [0, 0.05], 'balloon.drag_coefficient': [0.05, 1.5], 'radio.string_length': [0.3, 3],
    'damping.pivot': [0, 1], 'damping.lid_hinge': [0, 0.2], 'seesaw.left_arm': [0.2, 3],
    'seesaw.mass': [0, 2], 'seesaw.inertia': [0.001, 1, 'log'], 'seesaw.com_offset': [-1, 1],
    'start.sandbag_x': [-1.5, -0.01], 'start.sandbag_height': [0, 3], 'start.seesaw_angle': [-60, 60],
    'start.lid_angle': [0, 60], 'run.t_max': [0.5, 30], 'run.output_step': [1e-4, 0.05, 'log'],
    'run.step': [1e-5, 1e-2, 'log'], 'run.tolerance': [1e-14, 1e-4, 'log'], 'run.vertical_margin': [0, 10],
    'run.gravity': [1, 25], 'radio.switch_force': [0, 1], 'floor.restitution': [0, 1],
    'restitution.sandbag': [0, 1], 'restitution.rope': [0, 1], 'restitution.lid': [0, 1], 'restitution.stop': [0, 1],
    'friction.sandbag': [0, 1.5], 'friction.pivot': [0, 2], 'friction.lid_hinge': [0, 1],
    'rope.stiffness': [10, 1e8, 'log'], 'rope.damping': [0, 100],
  };
  const kSections = { balloon: 'Balloon', radio: 'Radio', damping: 'Damping', seesaw: 'The seesaw: its arm, mass and end stop',
                      floor: 'The floor', restitution: 'Restitution: impacts that bounce',
                      friction: 'Friction', rope: 'A rope that stretches' };
  const kNumberKinds = ['length', 'mass', 'density', 'angle', 'time', 'acceleration', 'positive'];
  const kSliderSteps = 1000;
  const kProbes = 40;  // slider positions checked for validity

  const number = (x) => String(Number(x.toPrecision(12)));
  // A decimal comma, as German and most of Europe write numbers ("0,7"), is a point to the library.
  const point = (text) => (/^\s*[-+]?\d*,\d+([eE][-+]?\d+)?\s*$/.test(text) ? text.replace(',', '.') : text);
  // And back: a number as the page's language writes it ("0,6" in German). Only what the panel
  // shows; what it sends (the link, the library, the TOML) keeps the point.
  const shown = (text) => (S.decimal !== '.' && /^\s*[-+]?\d*\.\d+([eE][-+]?\d+)?\s*$/.test(text) ? text.replace('.', S.decimal) : text);
  const rounded = (x) => String(Number(x.toPrecision(6)));  // for values the page works out
  const words = (key) => S.keyName(key, key.slice(key.indexOf('.') + 1).replace(/_/g, ' '));

  function element(tag, attrs, ...children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'class') e.className = v; else if (k === 'text') e.textContent = v; else e.setAttribute(k, v);
    }
    for (const c of children) if (c) e.append(c);
    return e;
  }

  const kSmall = '(max-width: 900px) and (orientation: portrait), (max-width: 600px)';
  // A number with its unit, as a screen reader says a slider's value.
  const unitWords = (unit) => unit.replace('^2', '²').replace('^3', '³');

  function create(form, keys, names, onChange) {
    const fields = new Map();  // key -> {spec, root, inputs, slider, error, reset}
    // What a blank field means for the keys a machine without them does not write: the key
    // table's own default (docs/inputs.md), a pair as its two numbers.
    const defaults = Object.fromEntries(keys.map((k) => [k.key, /^\[.*\]$/.test(k.default)
      ? k.default.slice(1, -1).split(',').map((x) => x.trim()) : k.default]));

    const groups = kGroups.map((g) => {
      const details = element('details', { class: 'group' });
      // On a phone or an upright tablet every section starts closed: the physics comes first.
      if (!g.closed && !window.matchMedia(kSmall).matches) details.open = true;
      const summary = element('summary', { text: S.t(g.title) });
      summary.append(element('span', { class: 'changed-count' }));
      details.append(summary);
      form.append(details);
      return { ...g, details };
    });

    for (const spec of keys) {
      const group = groups.find((g) => g.match(spec.key));
      const section = spec.key.slice(0, spec.key.indexOf('.'));
      if (group.closed && group.section !== section) {  // the extensions, by the part they change
        group.details.append(element('h3', { text: S.t(kSections[section] || section) }));
        group.section = section;
      }
      group.details.append(makeField(spec));
    }

    function makeField(spec) {
      const key = spec.key, id = `field-${key.replace(/\./g, '-')}`;
      const root = element('div', { class: `field kind-${spec.kind}`, 'data-key': key });
      const label = element('label', { for: id },
                            element('span', { class: 'name', text: words(key) }),
                            spec.unit ? document.createTextNode(' ') : null,
                            spec.unit ? element('span', { class: 'unit', text: `[${unitWords(spec.unit)}]` }) : null);
      const reset = element('button', { type: 'button', class: 'reset', title: S.t('back to the machine as loaded'),
                                        'aria-label': S.t('reset {key}', { key }) });
      reset.textContent = '↺';
      const row = element('div', { class: 'inputs' });
      const field = { spec, root, inputs: [], slider: null, reset, error: null };
      const send = (text, commit) => onChange(key, text, commit);

      if (spec.kind === 'text') {
        const select = element('select', { id });
        for (const choice of names[key] || []) select.append(element('option', { value: choice, text: choice }));
        select.addEventListener('change', () => send(select.value, true));
        field.inputs.push(select);
        row.append(select);
      } else if (spec.kind === 'flag') {
        const box = element('input', { id, type: 'checkbox' });
        box.addEventListener('change', () => send(box.checked ? 'true' : 'false', true));
        field.inputs.push(box);
        row.append(box, element('span', { class: 'flag-words', text: S.t('on') }));
      } else if (spec.kind === 'pair') {
        for (const [i, part] of ['dx', 'dh'].entries()) {
          const input = element('input', { id: i ? `${id}-dh` : id, type: 'text', inputmode: 'decimal',
                                          'aria-label': `${key} ${part}`, size: 6 });
          field.inputs.push(input);
          row.append(element('span', { class: 'part', text: part }), input);
        }
        const pairText = () => {
          const [a, b] = field.inputs.map((inp) => point(inp.value.trim()) || point(inp.placeholder));
          return field.inputs.every((inp) => !inp.value.trim()) ? null : `[${a}, ${b}]`;
        };
        for (const input of field.inputs) {
          input.addEventListener('input', () => send(pairText(), false));
          input.addEventListener('change', () => send(pairText(), true));
        }
      } else {
        const input = element('input', { id, type: 'text', inputmode: 'decimal', size: 9 });
        const moveSlider = () => {
          const v = Number(point(input.value.trim()) || point(input.placeholder));
          if (field.slider && input.value.trim() !== '' && Number.isFinite(v)) field.slider.value = String(Math.round(field.toSlider(v)));
        };
        input.addEventListener('input', () => { moveSlider(); send(point(input.value.trim()) || null, false); });
        input.addEventListener('change', () => send(point(input.value.trim()) || null, true));
        field.inputs.push(input);
        row.append(input);
        if (kNumberKinds.includes(spec.kind) && kRanges[key]) {
          const slider = element('input', { type: 'range', min: 0, max: kSliderSteps, step: 1, class: 'slider',
                                           'aria-label': words(key), tabindex: -1 });
          const [lo, hi, log] = kRanges[key];
          field.toSlider = (v) => kSliderSteps * (log ? Math.log(v / lo) / Math.log(hi / lo) : (v - lo) / (hi - lo));
          field.fromSlider = (p) => (log ? lo * Math.pow(hi / lo, p / kSliderSteps) : lo + (hi - lo) * p / kSliderSteps);
          const text = () => String(Number(field.fromSlider(Number(slider.value)).toPrecision(3)));
          // Said as the value with its unit, not the slider's position.
          field.speak = (v) => {
            const said = `${shown(String(Number(Number(v).toPrecision(4))))} ${spec.unit ? unitWords(spec.unit) : ''}`.trim();
            if (slider.getAttribute('aria-valuetext') !== said) slider.setAttribute('aria-valuetext', said);  // written only when it changes
          };
          slider.addEventListener('input', () => { input.value = shown(text()); field.speak(text()); send(text(), false); });
          slider.addEventListener('change', () => send(text(), true));
          field.slider = slider;
        }
      }
      reset.addEventListener('click', () => send(null, true));
      field.error = element('p', { class: 'error', role: 'alert' });
      field.error.hidden = true;
      root.append(label, row, reset);
      if (field.slider) root.append(field.slider);
      root.append(element('p', { class: 'help' }, S.keyHelp(key, spec.help) + ' ', element('code', { text: key })), field.error);
      fields.set(key, field);
      return root;
    }

    // What a blank field stands for: the value this run has (as to_toml writes it), or the
    // documented default of an extension that is off.
    function blankMeaning(key, values) {
      const eff = values.effective;
      if (key === 'geometry.hinge_distance' || key === 'geometry.hinge_angle') {
        const [dx, dh] = eff['geometry.hinge_offset'].pair;
        return key.endsWith('distance') ? rounded(Math.hypot(dx, dh)) : rounded(Math.atan2(dh, dx) * 180 / Math.PI);
      }
      const v = eff[key];
      // The knot's default is the lid's free edge, 2 r_L from the hinge (to_toml writes it only
      // where it is given).
      if (!v && key === 'geometry.rope_on_lid') return rounded(2 * eff['geometry.lid_half_length'].number);
      if (!v) return defaults[key] || '';
      if (v.pair) return v.pair.map(rounded);
      if (v.text !== undefined) return v.text;
      return rounded(v.number);
    }

    // The help of the field under the pointer or with the focus, in one box beside the panel
    // where there is room (over the drawing, never over another field); on a narrow screen in the
    // field itself, below its input, while it has the focus (a phone has no pointer to hover).
    const tip = element('div', { class: 'help-tip', role: 'tooltip' });
    tip.hidden = true;
    document.body.append(tip);
    let tipFor = null;
    function showTip(field) {
      const help = field.root.querySelector('.help');
      const panelBox = form.getBoundingClientRect();
      const room = window.innerWidth - panelBox.right;
      field.root.classList.remove('help-inline');
      if (room < 220) {  // no room beside the panel: inline, in the flow, with the focus only
        tip.hidden = true;
        tipFor = null;
        if (field.root.contains(document.activeElement)) field.root.classList.add('help-inline');
        return;
      }
      tip.textContent = '';
      for (const n of help.childNodes) tip.append(n.cloneNode(true));
      const r = field.root.getBoundingClientRect();
      tip.style.left = `${panelBox.right + 12}px`;
      tip.style.top = `${Math.max(4, r.top)}px`;
      tip.style.maxWidth = `${Math.min(360, room - 24)}px`;
      tip.hidden = false;
      tipFor = field;
    }
    function hideTip(field) {
      field.root.classList.remove('help-inline');
      if (tipFor !== field) return;
      const focused = field.root.contains(document.activeElement);
      if (focused || field.root.matches(':hover')) return;
      tip.hidden = true;
      tipFor = null;
    }
    for (const field of fields.values()) {
      field.root.addEventListener('mouseenter', () => showTip(field));
      field.root.addEventListener('mouseleave', () => { hideTip(field); const f = [...fields.values()].find((x) => x.root.contains(document.activeElement)); if (f && tip.hidden) showTip(f); });
      field.root.addEventListener('focusin', () => showTip(field));
      field.root.addEventListener('focusout', () => setTimeout(() => hideTip(field), 0));
    }
    form.closest('section').addEventListener('scroll', () => { if (tipFor) showTip(tipFor); }, { passive: true });

    return {
      // Shows the run's inputs: what the machine file and the changes give, blank (with the
      // value it stands for in grey) where nothing is given. The field being typed in is left alone.
      show(values, sets) {
        // Only what differs is written: a change of one key rewrites one field, not 36.
        const put = (el, prop, v) => { if (el[prop] !== v) el[prop] = v; };
        for (const [key, field] of fields) {
          const given = values.given[key], set = sets.get(key), blank = blankMeaning(key, values);
          const kind = field.spec.kind;
          if (field.root.classList.contains('changed') !== sets.has(key)) field.root.classList.toggle('changed');
          put(field.reset, 'hidden', !sets.has(key));
          if (field.inputs.includes(document.activeElement)) continue;
          if (kind === 'text') {
            put(field.inputs[0], 'value', set !== undefined ? set : given ? given.text : blank);
          } else if (kind === 'flag') {
            const on = set !== undefined ? set === 'true' : given ? given.number !== 0 : flagMeaning(key, values);
            put(field.inputs[0], 'checked', on);
          } else if (kind === 'pair') {
            let parts = ['', ''];
            if (set !== undefined) parts = set.replace(/[[\]\s]/g, '').split(',');
            else if (given && given.pair) parts = given.pair.map(number);
            field.inputs.forEach((inp, i) => { put(inp, 'value', shown(parts[i] || '')); put(inp, 'placeholder', shown(blank[i] || '')); });
          } else {
            const input = field.inputs[0];
            const text = set !== undefined ? set : given && given.number !== undefined ? number(given.number) : '';
            put(input, 'value', shown(text));
            put(input, 'placeholder', shown(blank));
            if (field.slider) {
              const v = Number(point(text) || blank);
              if (Number.isFinite(v)) {
                put(field.slider, 'value', String(Math.round(field.toSlider(v))));
                field.speak(v);
              }
            }
          }
        }
        // Each section's summary says how many of its values were changed.
        for (const details of form.querySelectorAll('details.group')) {
          const n = details.querySelectorAll('.field.changed').length;
          const mark = details.querySelector('summary .changed-count');
          const text = n ? ` · ${S.t('{n} changed', { n })}` : '';
          if (mark.textContent !== text) mark.textContent = text;
          details.classList.toggle('has-changes', n > 0);
        }
      },
      showError(key, message) {
        const field = fields.get(key);
        if (!field) return false;
        field.error.textContent = message;
        field.error.hidden = false;
        field.root.classList.add('invalid');
        const details = field.root.closest('details');
        if (details) details.open = true;
        return true;
      },
      clearErrors() {
        for (const field of fields.values()) {
          if (field.error.hidden) continue;
          field.error.hidden = true;
          field.error.textContent = '';
          field.root.classList.remove('invalid');
        }
      },
      field(key) { return fields.get(key); },
      // The slider positions to ask the library about: kProbes values across each slider.
      probes() {
        const out = [];
        for (const [key, field] of fields) {
          if (!field.slider) continue;
          const values = [];
          for (let i = 0; i < kProbes; ++i) values.push(number(field.fromSlider((i + 0.5) * kSliderSteps / kProbes)));
          out.push({ key, values });
        }
        return out;
      },
      // Where on its slider a value is refused (red hatching, with its range named in the help).
      showValidity(valid) {
        for (const [key, ok] of Object.entries(valid)) {
          const field = fields.get(key);
          if (!field || !field.slider) continue;
          field.validity = ok;
          const stops = [];
          ok.forEach((good, i) => {
            const a = (100 * i) / ok.length, b = (100 * (i + 1)) / ok.length;
            const c = good ? 'transparent' : 'rgba(210,0,0,0.75)';
            stops.push(`${c} ${a}%`, `${c} ${b}%`);
          });
          field.slider.style.setProperty('--refused', ok.every(Boolean) ? 'none' : `linear-gradient(to right, ${stops.join(', ')})`);
          field.slider.classList.toggle('partly-invalid', !ok.every(Boolean));
          field.slider.title = ok.every(Boolean) ? '' : S.t('red: values this machine refuses');
        }
      },
    };
  }

  // A flag that is not given is on when its extension is on in this run (floor.enabled: when
  // floor.restitution is given); to_toml writes the switches that are on.
  function flagMeaning(key, values) {
    if (key === 'balloon.drag') return Boolean(values.effective['balloon.drag_coefficient']);
    const v = values.effective[key];
    return Boolean(v) && v.number !== 0;
  }

  window.whatnextPanel = { create, point, shown };
})();
