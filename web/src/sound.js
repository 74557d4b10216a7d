// Sound, synthesised with WebAudio (nothing is loaded): a click at each impact and a short tune
// when the radio switches on (the sketch's punchline). Browsers let a page make sound only after
// the user has touched it; the audio is set up at the first click, tap or key and not before, and
// a sound that comes earlier is left out. Every sound (made, left out or muted) is logged in
// `log` and counted in body[data-sounds], which the tests read.
(function () {
  'use strict';

  function create() {
    let ctx = null, gesture = false;
    let muted = false;
    try { muted = localStorage.getItem('whatnext.muted') === 'true'; } catch (e) { /* not kept */ }
    const log = [];
    const note = (kind, what) => {
      log.push({ kind, what });
      document.body.dataset.sounds = String(log.filter((x) => x.what === 'played').length);
    };

    function unlock(e) {
      if (!e.isTrusted || gesture) return;
      gesture = true;
      const Ctx = window.AudioContext || window.webkitAudioContext;
      if (!Ctx) return;
      try {
        ctx = new Ctx();
        if (ctx.state === 'suspended') ctx.resume().catch(() => {});
      } catch (err) {
        ctx = null;  // no audio device: the page stays silent
      }
    }
    for (const type of ['pointerdown', 'keydown', 'touchstart']) document.addEventListener(type, unlock, { capture: true });

    // One tone: an oscillator shaped by a quick rise and an exponential fall.
    function tone(type, freq, start, length, level) {
      const osc = ctx.createOscillator(), gain = ctx.createGain();
      osc.type = type;
      osc.frequency.setValueAtTime(freq, start);
      gain.gain.setValueAtTime(0.0001, start);
      gain.gain.exponentialRampToValueAtTime(level, start + 0.008);
      gain.gain.exponentialRampToValueAtTime(0.0001, start + length);
      osc.connect(gain).connect(ctx.destination);
      osc.start(start);
      osc.stop(start + length + 0.02);
    }

    function play(kind, make) {
      if (muted) return note(kind, 'muted');
      if (!gesture || !ctx) return note(kind, gesture ? 'no audio' : 'before any gesture: silent');
      make(ctx.currentTime + 0.01);
      note(kind, 'played');
    }

    return {
      log,
      get muted() { return muted; },
      set muted(on) {
        muted = on;
        try { localStorage.setItem('whatnext.muted', String(on)); } catch (e) { /* not kept */ }
      },
      // A knock: a low square blip with a high tick on top, 60 ms.
      impact: () => play('impact', (t) => {
        tone('square', 140, t, 0.06, 0.18);
        tone('triangle', 1800, t, 0.025, 0.12);
      }),
      // The radio's jingle: a rising arpeggio and a held chord, about a second.
      radio: () => play('radio', (t) => {
        const notes = [523.25, 659.25, 783.99, 1046.5];  // C5 E5 G5 C6
        notes.forEach((f, i) => tone('triangle', f, t + 0.12 * i, 0.22, 0.2));
        for (const f of [523.25, 659.25, 783.99]) tone('sine', f, t + 0.5, 0.7, 0.12);
      }),
    };
  }

  window.whatnextSound = { create };
})();
