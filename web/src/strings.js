// The page's words in more than one language. The page is written in English; each other
// language is one table below from the English words (as they stand in index.html and the scripts,
// whitespace collapsed) to its own, plus patterns for the library's sentences (the outcome, the
// events and modes, the messages) that hold numbers. A word missing from a table stays English.
// Another language: one more entry in kLanguages with its name, table, patterns (outcomes, modes),
// messages (the library's errors), place (where a message says it comes from) and decimal sign.
(function () {
  'use strict';

  const de = {
    // index.html
    "whatnext: Kermit's What-Happens-Next machine": 'whatnext: Kermits Was-passiert-dann-Maschine',
    "Kermit's What-Happens-Next machine simulated exactly, in the browser: the same C++ core as the whatnext command line, compiled to WebAssembly.":
      'Kermits Was-passiert-dann-Maschine exakt simuliert, im Browser: derselbe C++-Kern wie das Kommandozeilenprogramm whatnext, nach WebAssembly übersetzt.',
    "Kermit's What-Happens-Next machine, simulated exactly": 'Kermits Was-passiert-dann-Maschine, exakt simuliert',
    Machine: 'Maschine',
    "Open a machine file (TOML or the paper's whatnext.inp)": 'Eine Maschinendatei öffnen (TOML oder whatnext.inp aus dem Artikel)',
    'Open file…': 'Datei öffnen…',
    'Copy a link that reopens this machine': 'Einen Link kopieren, der diese Maschine wieder öffnet',
    'Copy link': 'Link kopieren',
    Downloads: 'Herunterladen',
    Download: 'Herunterladen',
    'The machine as TOML, for whatnext run': 'Die Maschine als TOML, für whatnext run',
    'The events, as whatnext run --events writes them': 'Die Ereignisse, wie whatnext run --events sie schreibt',
    'events JSON': 'Ereignisse JSON',
    'The sampled run, as whatnext run --csv writes it': 'Der Lauf in Zeitschritten, wie whatnext run --csv ihn schreibt',
    'Projector mode: full screen, the machine large (F)': 'Beamer-Modus: Vollbild, die Maschine groß (F)',
    Projector: 'Beamer',
    'Keyboard controls (?)': 'Tastatur (?)',
    'Keyboard controls': 'Tastatur',
    'Sound on or off': 'Ton an oder aus',
    'Sound: on': 'Ton: an',
    'Sound: off': 'Ton: aus',
    Language: 'Sprache',
    'The machine': 'Die Maschine',
    'The machine drawn to scale': 'Die Maschine, maßstabsgetreu gezeichnet',
    'Not the values in the panel: the last run that worked.': 'Nicht die Werte der Eingabefelder: der letzte Lauf, der ging.',
    'Back to the start (Home)': 'Zurück zum Anfang (Pos1)',
    'Back to the start': 'Zurück zum Anfang',
    'Previous event (PageUp or [)': 'Voriges Ereignis (Bild↑ oder [)',
    'Previous event': 'Voriges Ereignis',
    'Play or pause (Space)': 'Abspielen oder anhalten (Leertaste)',
    Play: 'Abspielen',
    Pause: 'Anhalten',
    'Next event (PageDown or ])': 'Nächstes Ereignis (Bild↓ oder ])',
    'Next event': 'Nächstes Ereignis',
    speed: 'Tempo',
    'Slow motion (+ and −)': 'Zeitlupe (+ und −)',
    'slow motion ×10 near the events, fast through the quiet stretches': 'Zeitlupe ×10 bei den Ereignissen, schnell durch die ruhigen Strecken',
    'real time': 'Echtzeit',
    Time: 'Zeit',
    'What happens': 'Was passiert',
    'Loading the machine…': 'Die Maschine wird geladen…',
    Stop: 'Anhalten',
    'Events (click one to go there)': 'Ereignisse (eines anklicken, um dorthin zu gehen)',
    'Events (tap one to go there)': 'Ereignisse (eines antippen, um dorthin zu gehen)',
    event: 'Ereignis',
    mode: 'Phase',
    'The same run on the command line': 'Derselbe Lauf auf der Kommandozeile',
    Plots: 'Diagramme',
    'Compare with': 'Vergleichen mit',
    nothing: 'nichts',
    'another impact law': 'einem anderen Stoßgesetz',
    'all four impact laws': 'allen vier Stoßgesetzen',
    "the paper's Euler method": 'dem Euler-Verfahren des Artikels',
    'the previous parameters': 'den vorigen Parametern',
    'the rope that does not stretch': 'dem Seil, das sich nicht dehnt',
    'no friction': 'ohne Reibung',
    'This rope does not stretch: give it a stiffness (rope.stiffness) to compare it with the one that does not.': 'Dieses Seil dehnt sich nicht: geben Sie ihm eine Steifigkeit (rope.stiffness), um es mit dem zu vergleichen, das sich nicht dehnt.',
    'This machine has no friction: give friction.sandbag, friction.pivot or friction.lid_hinge to compare it with none.': 'Diese Maschine hat keine Reibung: geben Sie friction.sandbag, friction.pivot oder friction.lid_hinge an, um sie mit einer ohne zu vergleichen.',
    'Impact law to compare with': 'Stoßgesetz zum Vergleich',
    step: 'Schritt',
    Angles: 'Winkel',
    'Heights above the pivot': 'Höhen über der Wippenachse',
    'Energy and impact losses': 'Energie und Stoßverluste',
    'Rope tension': 'Seilkraft',
    'Drag across a plot to zoom in, double-click to zoom out, click to go to that time.':
      'Über ein Diagramm ziehen vergrößert, Doppelklick verkleinert, Klick geht zu diesem Zeitpunkt.',
    'Tap a plot to go to that time.': 'Ein Diagramm antippen geht zu diesem Zeitpunkt.',
    'Dashed vertical lines mark the events.': 'Gestrichelte senkrechte Linien markieren die Ereignisse.',
    'Energies are measured from the pivot\'s height: a mass below the pivot has negative potential energy, so the machine\'s energy E can be below zero.':
      'Energien zählen ab der Höhe der Wippenachse: eine Masse unterhalb der Achse hat negative Lageenergie, daher kann die Energie E der Maschine unter null liegen.',
    Parameters: 'Parameter',
    'Back to the machine as loaded': 'Zurück zur Maschine, wie sie geladen wurde',
    'Reset all': 'Alles zurücksetzen',
    'Every change runs the machine again at once. Angles in degrees, everything else in SI units. A blank field takes the value shown in grey.':
      'Jede Änderung rechnet die Maschine sofort neu. Winkel in Grad, alles andere in SI-Einheiten. Ein leeres Feld nimmt den grau gezeigten Wert. Dezimalkomma oder -punkt.',
    'The same C++ library as the': 'Dieselbe C++-Bibliothek wie das Programm',
    'command, compiled to WebAssembly. Plots: uPlot.': ', nach WebAssembly übersetzt. Diagramme: uPlot.',
    Keyboard: 'Tastatur',
    Space: 'Leertaste',
    'play / pause': 'abspielen / anhalten',
    'back / forward 1 ms (with': 'zurück / vor 1 ms (mit',
    Shift: 'Umschalt',
    ': 10 ms)': ': 10 ms)',
    PageUp: 'Bild↑',
    PageDown: 'Bild↓',
    or: 'oder',
    'previous / next event': 'voriges / nächstes Ereignis',
    Home: 'Pos1',
    End: 'Ende',
    'start / end of the run': 'Anfang / Ende des Laufs',
    'faster / slower (real time … 1/50)': 'schneller / langsamer (Echtzeit … 1/50)',
    'projector mode on / off (': 'Beamer-Modus an / aus (',
    'leaves full screen)': 'verlässt das Vollbild)',
    M: 'M',
    'sound on / off': 'Ton an / aus',
    'this help': 'diese Hilfe',
    Close: 'Schließen',
    'Run it': 'Rechnen',
    "Don't run": 'Nicht rechnen',
    'Choose a preset': 'Eine Maschine wählen',

    // app.js
    'Running… {where}{secs} s so far.': 'Rechnet… {where}bisher {secs} s.',
    't = {t} s of {tMax} s; ': 't = {t} s von {tMax} s; ',
    'This page cannot start its worker here ({why}). Opened from a folder on the disk, use whatnext.html (the page in one file); or serve the folder (./run.sh web).':
      // Without the browser's reason ({why}), which is English whatever the page's language.
      'Die Seite kann hier ihren Worker nicht starten. Aus einem Ordner auf der Festplatte geöffnet: whatnext.html verwenden (die Seite in einer Datei), oder den Ordner bereitstellen (./run.sh web).',
    'the worker did not start': 'der Worker ist nicht gestartet',
    'its length is not that of base64 text': 'seine Länge ist nicht die eines Base64-Texts',
    'it is not text in UTF-8': 'er ist kein Text in UTF-8',
    'This run': 'Dieser Lauf',
    'The run to compare with': 'Der Vergleichslauf',
    '{what} takes {steps} steps of the {integrator} method (t_max {tMax} s at a step of {step} s): the page may work on it for minutes. Run it anyway? (It can be stopped.)':
      '{what} braucht {steps} Schritte des Verfahrens {integrator} (t_max {tMax} s mit Schrittweite {step} s): das kann Minuten dauern. Trotzdem rechnen? (Er lässt sich anhalten.)',
    'not started ({steps} steps)': 'nicht gestartet ({steps} Schritte)',
    'This machine cannot be run': 'Diese Maschine lässt sich nicht rechnen',
    'Stopped before the run was done': 'Angehalten, bevor der Lauf fertig war',
    'Not started': 'Nicht gestartet',
    'Not run': 'Nicht gerechnet',
    'The drawing and plots still show the last run that worked.': 'Zeichnung und Diagramme zeigen weiter den letzten Lauf, der ging.',
    'Nothing to compare with: that run was stopped.': 'Kein Vergleich: dieser Lauf wurde angehalten.',
    'Nothing to compare with: {message}': 'Kein Vergleich: {message}',
    'it holds characters that are not URL-safe base64': 'er enthält Zeichen, die kein URL-sicheres Base64 sind',
    'it holds {bytes} bytes, more than the {most} a machine file may have': 'er hat {bytes} Bytes, mehr als die {most}, die eine Maschinendatei haben darf',
    '{name} is not opened: it has {bytes} bytes, more than the {most} bytes a machine file may have.':
      '{name} wird nicht geöffnet: die Datei hat {bytes} Bytes, mehr als die {most} Bytes, die eine Maschinendatei haben darf.',
    "The link's machine={given} is not one of this page's machines ({ids}).": 'machine={given} im Link ist keine Maschine dieser Seite ({ids}).',
    "The link's file (text=) cannot be read: {why}.": 'Die Datei im Link (text=) ist nicht lesbar: {why}.',
    'The link names a file ({given}) but does not hold it (no text=).': 'Der Link nennt eine Datei ({given}), enthält sie aber nicht (kein text=).',
    'The link\'s part "{given}" is not a key (keys look like geometry.rope_length) and was left out.':
      'Der Teil „{given}“ des Links ist kein Schlüssel (Schlüssel sehen aus wie geometry.rope_length) und wurde weggelassen.',
    "The link's compare={given} is not a comparison (law:NAME with NAME one of {laws}; laws:; euler:STEP with a step in seconds above 0) and was left out.":
      'compare={given} im Link ist kein Vergleich (law:NAME mit NAME aus {laws}; laws:; euler:SCHRITT mit einer Schrittweite in Sekunden über 0) und wurde weggelassen.',
    "The link's machine does not run ({problem}).": 'Die Maschine des Links lässt sich nicht rechnen ({problem}).',
    "This is {title} without the link's changes.": 'Zu sehen ist {title} ohne die Änderungen des Links.',
    'Copy this link; it opens this machine:': 'Diesen Link kopieren; er öffnet diese Maschine:',
    'Link copied: it opens this machine.': 'Link kopiert: er öffnet diese Maschine.',
    'This address works on this computer only: serve the page (./run.sh web --lan, or any web server) to share it.':
      'Diese Adresse gilt nur auf diesem Computer: zum Teilen die Seite bereitstellen (./run.sh web --lan oder ein beliebiger Webserver).',
    'Outcome: {sentence}.': 'Ergebnis: {sentence}.',
    'Dashed, {label}: {sentence}.': 'Gestrichelt, {label}: {sentence}.',
    'impact law {law}': 'Stoßgesetz {law}',
    'Euler, step {step} s': 'Euler, Schritt {step} s',
    'previous parameters': 'vorige Parameter',
    'Change a parameter: the run before the change is then drawn dashed.': 'Einen Parameter ändern: der Lauf vor der Änderung wird dann gestrichelt gezeichnet.',
    'dashed in the plots, blue outline in the drawing': 'gestrichelt in den Diagrammen, blauer Umriss in der Zeichnung',
    'Last run: {ms} ms in WebAssembly, {events} events, {states} states.': 'Letzter Lauf: {ms} ms in WebAssembly, {events} Ereignisse, {states} Zustände.',
    'end of the run (Space plays it again)': 'Ende des Laufs (Leertaste spielt ihn noch einmal)',
    'end of the run (▶ plays it again)': 'Ende des Laufs (▶ spielt ihn noch einmal)',
    'paused (Space plays)': 'angehalten (Leertaste spielt ab)',
    'paused (▶ plays)': 'angehalten (▶ spielt ab)',
    'slow motion ×{x}': 'Zeitlupe ×{x}',
    'fast forward ×{x}': 'Zeitraffer ×{x}',
    'quiet stretch: {words}': 'ruhige Strecke: {words}',
    'event at {t} s: {words}': 'Ereignis bei {t} s: {words}',
    'That CSV would have {rows} rows: too many for a browser. Raise run.output_step, or use the command line (see "The same run on the command line").':
      'Diese CSV hätte {rows} Zeilen: zu viele für einen Browser. run.output_step erhöhen oder die Kommandozeile nehmen (siehe „Derselbe Lauf auf der Kommandozeile“).',
    'Example 1': 'Beispiel 1', 'Example 2': 'Beispiel 2', 'Example 3': 'Beispiel 3', 'Example 4': 'Beispiel 4',
    'Example 1 with the radio': 'Beispiel 1 mit dem Radio',
    'Example 1 + radio': 'Beispiel 1 + Radio', 'Konstanz (built)': 'Konstanz (gebaut)',
    'file: {name}': 'Datei: {name}',
    'one hard pull of the rope opens the lid': 'ein harter Ruck am Seil öffnet den Deckel',
    'the taut rope pulls the lid open': 'das straffe Seil zieht den Deckel auf',
    'sandbag on the level seesaw: the lid never opens': 'Sandsack auf der waagrechten Wippe: der Deckel öffnet nie',
    'a hard hit throws the lid up; it never opens': 'ein harter Schlag wirft den Deckel hoch; er öffnet nie',
    'the balloon switches the radio on': 'der Ballon schaltet das Radio ein',
    "The students' machine (Konstanz)": 'Die Maschine der Studierenden (Konstanz)',
    'built with a real party balloon: the radio stays off': 'gebaut mit einem echten Partyballon: das Radio bleibt aus',
    'Energy from the pivot\'s height: below it, potential energy is negative.': 'Energie ab der Höhe der Wippenachse: darunter ist die Lageenergie negativ.',

    // panel.js
    Geometry: 'Geometrie',
    Masses: 'Massen',
    'Air and balloon': 'Luft und Ballon',
    Start: 'Anfang',
    'Run: integrator and impact law': 'Lauf: Integrator und Stoßgesetz',
    'Extensions beyond the paper': 'Erweiterungen über den Artikel hinaus',
    Balloon: 'Ballon', Radio: 'Radio', Damping: 'Dämpfung', 'The seesaw: its arm, mass and end stop': 'Die Wippe: Arm, Masse und Anschlag',
    'The floor': 'Der Boden',
    'Restitution: impacts that bounce': 'Stoßzahlen: Stöße, die zurückfedern',
    Friction: 'Reibung',
    'A rope that stretches': 'Ein Seil, das sich dehnt',
    'back to the machine as loaded': 'zurück zur Maschine, wie sie geladen wurde',
    on: 'an',
    'reset {key}': '{key} zurücksetzen',
    'red: values this machine refuses': 'rot: Werte, die diese Maschine nicht annimmt',
    'valid from {lo} to {hi}': 'gültig von {lo} bis {hi}',

    // plots.js
    'angle [°]': 'Winkel [°]', 'height [m]': 'Höhe [m]', 'energy [J]': 'Energie [J]', 'tension [N]': 'Seilkraft [N]',
    'φS seesaw': 'φS Wippe', 'φL lid': 'φL Deckel', sandbag: 'Sandsack', 'balloon centre': 'Ballonmitte', 'lid limit': 'Grenze durch den Deckel',
    'machine E': 'Maschine E', 'lost (impacts, damping)': 'verloren (Stöße, Dämpfung)', 'E + lost': 'E + verloren', 'rope tension': 'Seilkraft',
    dashed: 'gestrichelt',
    energy: 'Energie',
    impulse: 'Kraftstoß', sandbag: 'Sandsack', rope: 'Seil', lid: 'Deckel',
    stop: 'Anschlag', 'floor on seesaw': 'Boden auf Wippe', 'floor on sandbag': 'Boden auf Sandsack',
    'not the {law} law: {note}': 'nicht das Gesetz {law}: {note}',
    // The reasons an impact takes the rope law instead of the one chosen (src/core/contact_decision.cpp,
    // impact_laws.cpp), shown in the timeline.
    'the jerk comes with a bounce on the floor, which no single law covers: the rope law':
      'mit dem Ruck prallt etwas vom Boden ab, was kein einzelnes Gesetz abdeckt: das Seilgesetz',
    'the jerk also presses the lid onto the box, which no single law covers: perfectly inelastic (rope law)':
      'der Ruck drückt auch den Deckel auf die Kiste, was kein einzelnes Gesetz abdeckt: vollkommen unelastisch (Seilgesetz)',
    'the law has no finite solution at this state: perfectly inelastic (rope law)':
      'das Gesetz hat in diesem Zustand keine endliche Lösung: vollkommen unelastisch (Seilgesetz)',
    'no sandbag takes part in this jerk, so linear momentum says nothing: perfectly inelastic (rope law)':
      'kein Sandsack ist an diesem Ruck beteiligt, daher sagt der Impulssatz nichts: vollkommen unelastisch (Seilgesetz)',
    'the law would drive a touching contact (the lid into the box, or the sandbag into the arm): perfectly inelastic (rope law)':
      'das Gesetz triebe einen berührenden Kontakt ineinander (den Deckel in die Kiste oder den Sandsack in den Arm): vollkommen unelastisch (Seilgesetz)',
    // machine.js
    'sandbag {d} m out': 'Sandsack {d} m draußen',
    'balloon {d} m up': 'Ballon {d} m oben',
    'each law in its colour: outlines in the drawing, dashes in the plots': 'jedes Gesetz in seiner Farbe: Umrisse in der Zeichnung, Striche in den Diagrammen',

    // The header's menus, the forces, the energy bars, the "why", the QR code
    'Share this machine: a link, or a QR code to scan': 'Diese Maschine teilen: ein Link oder ein QR-Code zum Scannen',
    Share: 'Teilen',
    'A QR code of the link, to scan with a phone': 'Ein QR-Code des Links, zum Scannen mit dem Handy',
    'QR code': 'QR-Code',
    'QR code of this machine': 'QR-Code dieser Maschine',
    'QR code of the link': 'QR-Code des Links',
    'This link is too long for a QR code ({n} characters): use Copy link.': 'Dieser Link ist für einen QR-Code zu lang ({n} Zeichen): Link kopieren benutzen.',
    'Download the machine and its run': 'Die Maschine und ihren Lauf herunterladen',
    Sound: 'Ton',
    'Forces and velocities drawn on the machine (V)': 'Kräfte und Geschwindigkeiten an der Maschine (V)',
    Forces: 'Kräfte',
    'forces and velocities on / off': 'Kräfte und Geschwindigkeiten an / aus',
    Show: 'Zeigen',
    'Energy bars': 'Energiebalken',
    'Why? The physics behind what you see': 'Warum? Die Physik hinter dem Bild',
    'Why?': 'Warum?',
    'What each impact law keeps and loses, and what a real rope does': 'Was jedes Stoßgesetz erhält und verliert, und was ein echtes Seil tut',
    'each law in its colour; in the drawing one at a time (choose it below)': 'jedes Gesetz in seiner Farbe; in der Zeichnung eines nach dem anderen (unten wählen)',
    '{law} (this run, filled)': '{law} (dieser Lauf, gefüllt)',
    '{law} (outline)': '{law} (Umriss)',
    'last event at {t} s: {words}': 'letztes Ereignis bei {t} s: {words}',
    'no event yet': 'noch kein Ereignis',
    '{t} s: {words}': '{t} s: {words}',
    '{n} changed': '{n} geändert',
    'Arrows (scale at the upper right): green gravity, purple the rope, blue the arm, the stop and the floor, orange velocities; red at an impact its impulses. An arrow cut by two bars is longer than drawn.':
      'Pfeile (Maßstab rechts oben): grün die Schwerkraft, violett das Seil, blau der Arm, der Anschlag und der Boden, orange Geschwindigkeiten; rot bei einem Stoß seine Kraftstöße. Ein Pfeil mit zwei Querstrichen ist länger als gezeichnet.',
    'gravity on the sandbag': 'Schwerkraft auf den Sandsack', 'gravity on the lid': 'Schwerkraft auf den Deckel',
    'gravity on the seesaw': 'Schwerkraft auf die Wippe', 'the rope on the sandbag': 'Seil auf den Sandsack',
    'the rope on the lid': 'Seil auf den Deckel', 'the arm on the sandbag': 'Arm auf den Sandsack',
    'the stop on the sandbag': 'Anschlag auf den Sandsack', 'the floor on the seesaw': 'Boden auf die Wippe',
    'the floor on the sandbag': 'Boden auf den Sandsack', 'velocity of the sandbag': 'Geschwindigkeit des Sandsacks',
    "velocity of the lid's edge": 'Geschwindigkeit der Deckelkante',
    'impulse of the arm on the sandbag': 'Kraftstoß des Arms auf den Sandsack', 'impulse of the rope on the sandbag': 'Kraftstoß des Seils auf den Sandsack',
    'impulse of the rope on the lid': 'Kraftstoß des Seils auf den Deckel', 'impulse of the stop': 'Kraftstoß des Anschlags',
    'impulse of the floor on the seesaw': 'Kraftstoß des Bodens auf die Wippe', 'impulse of the floor on the sandbag': 'Kraftstoß des Bodens auf den Sandsack',
    "impulse of the latch on the lid (at its edge)": 'Kraftstoß der Raste auf den Deckel (an seiner Kante)',
    "impulse of the box on the lid (at its edge)": 'Kraftstoß der Kiste auf den Deckel (an seiner Kante)',
    'sandbag, kinetic': 'Sandsack, kinetisch', 'sandbag, potential': 'Sandsack, potentiell', 'lid, kinetic': 'Deckel, kinetisch',
    'lid, potential': 'Deckel, potentiell', 'seesaw, kinetic': 'Wippe, kinetisch', 'seesaw, potential': 'Wippe, potentiell',
    'rope, spring': 'Seil, Feder', 'balloon, kinetic and lift': 'Ballon, kinetisch und Auftrieb', 'lost in impacts': 'bei Stößen verloren',
    'friction heat': 'Reibungswärme', damping: 'Dämpfung', "lid's work on the balloon": 'Arbeit des Deckels am Ballon',
    'Sum {sum} J = energy at the start {start} J': 'Summe {sum} J = Energie am Anfang {start} J',
    "Zero of potential energy: the sandbag and the seesaw at the pivot's height, the lid lying flat (at its hinge's height), the balloon's lift at the box's top. Below the zero a potential energy is negative (a bar to the left).":
      'Nullpunkt der potentiellen Energie: Sandsack und Wippe in Höhe der Achse, der Deckel flach liegend (in Höhe seines Scharniers), der Auftrieb des Ballons an der Oberkante der Kiste. Unter dem Nullpunkt ist eine potentielle Energie negativ (ein Balken nach links).',
    'What each impact law keeps and loses': 'Was jedes Stoßgesetz erhält und was es verliert',
    'When the rope snaps straight (or the sandbag lands), the speeds jump in no time. The paper offers four laws for the jump; each keeps something else:':
      'Wenn das Seil ruckartig straff wird (oder der Sandsack landet), springen die Geschwindigkeiten ohne Zeitverlust. Der Artikel bietet vier Gesetze für den Sprung an; jedes erhält etwas anderes:',
    "rope (the paper's eq. 7): the jerk is perfectly inelastic, like clay on clay. After it the sandbag and the lid move together as the straight rope lets them; the kinetic energy they lose is the most any law may lose.":
      'rope (Gl. 7 des Artikels): der Ruck ist vollkommen unelastisch, wie Knete auf Knete. Danach bewegen sich Sandsack und Deckel gemeinsam, wie das gestreckte Seil es zulässt; sie verlieren so viel kinetische Energie, wie ein Gesetz höchstens verlieren darf.',
    "angular-momentum-sum: keeps the sum of the sandbag's angular momentum about the pivot and the lid's about its hinge. It loses less kinetic energy than the rope law, and on some machines can even gain some.":
      'angular-momentum-sum: erhält die Summe der Drehimpulse des Sandsacks um die Achse und des Deckels um sein Scharnier. Es verliert weniger kinetische Energie als das Seilgesetz und kann an manchen Maschinen sogar welche gewinnen.',
    'kinetic-energy: keeps the kinetic energy: an elastic jerk, nothing lost. The lid leaves faster than under the rope law.':
      'kinetic-energy: erhält die kinetische Energie: ein elastischer Ruck, nichts geht verloren. Der Deckel fliegt schneller los als beim Seilgesetz.',
    "linear-momentum: keeps the linear momentum of the sandbag and the lid's centre. It can make energy out of nothing: the paper calls it unphysical.":
      'linear-momentum: erhält den Impuls von Sandsack und Deckelmitte. Es kann Energie aus dem Nichts erzeugen: der Artikel nennt es unphysikalisch.',
    "(this run's law)": '(das Gesetz dieses Laufs)',
    'A real rope stretches: the answer of a stiff rope': 'Ein echtes Seil dehnt sich: die Antwort eines steifen Seils',
    'A stiff rope that stretches gives none of the four in general: it gives the rope law followed by a rebound. The rope springs back with Newton\'s restitution e(ζ), which depends only on the rope\'s damping ratio ζ: e = 1 for an undamped rope (an elastic bounce), e = 0.135 at ζ = 1, almost 0 for a well damped rope (the rope law). That is why "the rope that does not stretch" can change when the lid opens: a rope that stretches springs back.':
      'Ein steifes Seil, das sich dehnt, ergibt im Allgemeinen keines der vier: es ergibt das Seilgesetz, gefolgt von einem Rückprall. Das Seil federt mit Newtons Stoßzahl e(ζ) zurück, die nur vom Dämpfungsgrad ζ des Seils abhängt: e = 1 für ein ungedämpftes Seil (ein elastischer Stoß), e = 0,135 bei ζ = 1, fast 0 für ein stark gedämpftes Seil (das Seilgesetz). Darum kann „das Seil, das sich nicht dehnt“ ändern, wann der Deckel aufgeht: ein Seil, das sich dehnt, federt zurück.',
    "rope's damping ratio ζ": 'Dämpfungsgrad ζ des Seils',
    'ζ = {z}: e(ζ) = {e}': 'ζ = {z}: e(ζ) = {e}',
    "The lid's speed right after the first jerk, from runs of this machine by the library: under each law, and under the rope law with the rebound e(ζ) (restitution.rope).":
      'Die Geschwindigkeit des Deckels direkt nach dem ersten Ruck, aus Läufen dieser Maschine durch die Bibliothek: unter jedem Gesetz und unter dem Seilgesetz mit dem Rückprall e(ζ) (restitution.rope).',
    'rope law with the rebound e(ζ)': 'Seilgesetz mit Rückprall e(ζ)',
    law: 'Gesetz',
    "lid's speed after the jerk [°/s]": 'Deckel nach dem Ruck [°/s]',
    'no jerk': 'kein Ruck',
    'Why the lid latches (the radio machines)': 'Warum der Deckel einrastet (die Maschinen mit Radio)',
    "With a radio, the lid latches open at the angle where it counts as open and the rope is let go. The latch is an impact: it stops the lid at once, and the lid's kinetic energy goes into the latch. The timeline shows the energy before and after it and the latch's impulse on the lid, and the energy bars count it with the impacts' losses. In the built machine (Konstanz) the seesaw then lands on the floor and the sandbag slides to the end stop: those impacts lose energy too, and the floor and the stop hold them (their reactions in the forces).":
      'Mit Radio rastet der Deckel bei dem Winkel ein, bei dem er als offen gilt, und das Seil wird losgelassen. Das Einrasten ist ein Stoß: es hält den Deckel sofort an, und seine kinetische Energie geht in die Raste. Die Zeitleiste zeigt die Energie davor und danach und den Kraftstoß der Raste auf den Deckel, und die Energiebalken zählen sie bei den Stoßverlusten. In der gebauten Maschine (Konstanz) landet die Wippe dann auf dem Boden und der Sandsack rutscht an den Anschlag: auch diese Stöße verlieren Energie, und Boden und Anschlag halten sie (ihre Gegenkräfte bei den Kräften).',
    "Would the students' machine switch the radio on? (Konstanz)": 'Würde die Maschine der Studierenden das Radio einschalten? (Konstanz)',
    "No. The machine students build opens its lid, but its balloon is a real party balloon: its rubber skin and ribbon weigh about 2 g, and the air drags on it. Its lift is small and the skin takes more than half of it: when the string is straight it pulls about 0.02 N, and the switch needs 0.03 N. So the radio stays off. The paper's sketch jokes that the machine may not do its job; with a real balloon it does not. The paper's balloon has no skin and no drag: that idealised machine is examples/konstanz-ideal.toml (load it with Open file…), and there the radio comes on.":
      'Nein. Die Maschine der Studierenden öffnet ihren Deckel, aber ihr Ballon ist ein echter Partyballon: seine Gummihaut und das Band wiegen etwa 2 g, und die Luft bremst ihn. Sein Auftrieb ist klein, und die Haut nimmt mehr als die Hälfte davon: Wenn die Schnur gestreckt ist, zieht sie mit etwa 0,02 N, und der Schalter braucht 0,03 N. Also bleibt das Radio aus. Die Skizze im Artikel scherzt, dass die Maschine ihre Aufgabe vielleicht nicht erfüllt; mit einem echten Ballon erfüllt sie sie nicht. Der Ballon des Artikels hat keine Haut und keinen Luftwiderstand: Diese idealisierte Maschine ist examples/konstanz-ideal.toml (mit „Datei öffnen…“ laden), und dort geht das Radio an.',
    'What makes it work: a bigger balloon and a lighter switch. A balloon of 0.11 m radius (filled to 22 cm, it still fits the box) and a switch of 0.01 N (a foil flap a third as stiff) switch the radio on in 99.5 % of builds (docs/extensions.md).':
      'Was sie zum Laufen bringt: ein größerer Ballon und ein leichterer Schalter. Ein Ballon mit 0,11 m Radius (auf 22 cm aufgeblasen passt er noch in die Kiste) und ein Schalter mit 0,01 N (eine Folienklappe, ein Drittel so steif) schalten das Radio in 99,5 % der Aufbauten ein (docs/extensions.md).',
    'Try it: the build that works': 'Ausprobieren: der Aufbau, der funktioniert',
    'Why energies can be negative': 'Warum Energien negativ sein können',
    "Potential energy is measured from a chosen zero: here the pivot's height (the lid: lying flat). A sandbag below the pivot has negative potential energy, so the machine's energy E can be below zero. Only differences matter: what is lost at an impact is the same whatever the zero.":
      'Potentielle Energie wird von einem gewählten Nullpunkt aus gemessen: hier die Höhe der Achse (beim Deckel: flach liegend). Ein Sandsack unter der Achse hat negative potentielle Energie, also kann die Energie E der Maschine unter null liegen. Nur Differenzen zählen: was bei einem Stoß verloren geht, ist bei jedem Nullpunkt gleich.',
  };

  // The parameters' names and help (the library's list, docs/inputs.md), by key.
  const deKeys = {
    'geometry.seesaw_right_arm': ['Wippe, rechter Arm', 'r_H: Achse bis zum Seilende der Wippe'],
    'geometry.lid_half_length': ['halbe Deckellänge', 'r_L: halbe Länge des Deckels'],
    'geometry.rope_length': ['Seillänge', 'l: das Seil von der Wippe zur Deckelkante'],
    'geometry.hinge_distance': ['Abstand des Scharniers', 'Achse bis zum Scharnier des Deckels'],
    'geometry.hinge_angle': ['Winkel des Scharniers', 'unter der Waagrechten, von der Achse aus'],
    'geometry.hinge_offset': ['Lage des Scharniers', '[dx, dh]: Scharnier dx rechts und dh unter der Achse (statt Abstand und Winkel)'],
    'geometry.rope_on_lid': ['Knoten auf dem Deckel', 'wo das Seil angebunden ist: vom Scharnier aus entlang des Deckels (Abb. 3 des Artikels: r_L, die Mitte)'],
    'masses.sandbag': ['Sandsack', 'm_S: der Sandsack (eine Punktmasse)'],
    'masses.lid': ['Deckel', 'm_L: der Deckel (eine gleichmäßige Platte)'],
    'air.density': ['Dichte der Luft', 'Dichte der Luft'],
    'air.helium_density': ['Dichte des Heliums', 'Dichte des Heliums im Ballon'],
    'balloon.radius': ['Ballonradius', 'r_B'],
    'balloon.model': ['Ballonmodell', 'program (a = g (rho_Luft − rho_He) / rho_Luft), lagrangian (/ rho_He) oder added-mass (/ (rho_He + rho_Luft / 2))'],
    'balloon.rubber_mass': ['Gummimasse', 'das Gummi des Ballons: Gewicht und Trägheit'],
    'balloon.drag': ['Luftwiderstand', 'an: quadratischer Luftwiderstand 1/2 rho_Luft Cd pi r_B² v|v|'],
    'balloon.drag_coefficient': ['Widerstands\u00adbeiwert', 'Cd des Luftwiderstands (eine Kugel); ihn anzugeben schaltet den Widerstand ein'],
    'radio.enabled': ['Radio', 'an: nach lid_open weiterrechnen, bis die Ballonschnur das Radio einschaltet'],
    'radio.switch_offset': ['Lage des Schalters', '[dx, dh]: der Schalter des Radios dx rechts und dh über der oberen rechten Ecke der Kiste'],
    'radio.string_length': ['Schnurlänge', 'die Ballonschnur, Mitte bis Schalter'],
    'damping.pivot': ['Achse', 'zähes Moment −c phiS\' an der Achse der Wippe'],
    'damping.lid_hinge': ['Scharnier', 'zähes Moment −c phiL\' am Scharnier des Deckels'],
    'seesaw.left_arm': ['linker Arm', 'Achse bis zum Ende des linken Arms'],
    'seesaw.mass': ['Masse der Wippe', 'eine Wippe mit Masse: ein gleichmäßiger Balken von −left_arm bis r_H, außer inertia/com_offset sind angegeben'],
    'seesaw.inertia': ['Trägheitsmoment', 'das Trägheitsmoment der Wippe um die Achse'],
    'seesaw.com_offset': ['Schwerpunkt', 'der Schwerpunkt der Wippe längs des Balkens ab der Achse, + zum Seilende hin'],
    'seesaw.end_stop': ['Anschlag', 'an: eine Kante am Ende des linken Arms hält den Sandsack auf, der dann dort mitfährt (braucht seesaw.left_arm)'],
    'radio.switch_force': ['Schaltkraft', 'so stark muss die Schnur ziehen, um den Schalter des Radios umzulegen (ein Wippschalter); 0: jeder Zug'],
    'floor.enabled': ['Boden', 'an: der Boden, auf dem die Kiste steht; die Enden der Wippe und der Sandsack stehen darauf (braucht seesaw.left_arm)'],
    'floor.restitution': ['Stoßzahl', 'Newtons Stoßzahl für Stöße auf den Boden, 0 (sie bleiben liegen) bis 1 (sie springen ebenso schnell zurück); sie anzugeben schaltet den Boden ein'],
    'restitution.sandbag': ['Stoßzahl Sandsack', 'Newtons Stoßzahl für das Landen des Sandsacks auf dem Arm: 0 (er bleibt) bis 1'],
    'restitution.rope': ['Stoßzahl Seil', 'Newtons Stoßzahl für den Ruck des Seils: 0 (das Seilgesetz) bis 1 (das Seil federt ebenso schnell zurück)'],
    'restitution.lid': ['Stoßzahl Deckel', 'Newtons Stoßzahl für das Landen des Deckels auf der Kiste: 0 bis 1'],
    'restitution.stop': ['Stoßzahl Anschlag', 'Newtons Stoßzahl für den Sandsack am Anschlag: 0 bis 1 (braucht seesaw.end_stop)'],
    'rope.stiffness': ['Steifigkeit des Seils', 'ein Seil, das sich dehnt: eine einseitige Feder mit Dämpfer, die mit k (Abstand − l_R) + c Abstand\' zieht und nie drückt; kein Stoßgesetz (docs/impact.md)'],
    'rope.damping': ['Dämpfung des Seils', 'c des Seils, das sich dehnt (braucht rope.stiffness)'],
    'friction.pivot': ['Reibung Achse', 'Coulombsches Reibmoment an der Achse der Wippe: sie dreht sich nur, solange die übrigen Momente es übersteigen, gegen es (braucht eine Wippe mit Masse)'],
    'friction.lid_hinge': ['Reibung Scharnier', 'Coulombsches Reibmoment am Scharnier des Deckels: er dreht sich nur, solange die übrigen Momente es übersteigen, gegen es'],
    'friction.sandbag': ['Reibung Sandsack', 'Coulombs Reibungszahl μ zwischen Sandsack und Arm: er haftet, solange der Zug längs des Arms höchstens μ mal den Druck des Arms erreicht, sonst gleitet er gegen μ mal ihn; 0: er gleitet frei (wie im Aufsatz)'],
    'start.sandbag_x': ['Sandsack x', 'Anfangslage des Sandsacks, waagrecht ab der Achse (< 0)'],
    'start.sandbag_height': ['Sandsack Höhe', 'Anfangshöhe des Sandsacks über der Achse'],
    'start.seesaw_angle': ['Winkel der Wippe', 'phiS0, positiv = linker Arm unten'],
    'start.lid_angle': ['Winkel des Deckels', 'phiL0, der Ruhewinkel (tiefste Lage) des Deckels'],
    'run.t_max': ['Ende', 'Ende der simulierten Zeit'],
    'run.output_step': ['Ausgabeschritt', 'Abstand der CSV-/.dat-Zeilen'],
    'run.integrator': ['Integrator', 'adaptive, euler oder rk4'],
    'run.step': ['Schrittweite', 'Zeitschritt von euler und rk4'],
    'run.tolerance': ['Toleranz', 'adaptive: Fehlertoleranz pro Schritt (abs. und rel.), 1e-15 bis 1e-3'],
    'run.impact_law': ['Stoßgesetz', 'rope, angular-momentum-sum, kinetic-energy oder linear-momentum'],
    'run.vertical_margin': ['Abstand zur Senkrechten', 'so weit vor 90° anhalten'],
    'run.gravity': ['Schwere\u00adbeschleunigung', 'g'],
  };

  // The library's sentences with numbers: the outcome, the events, the modes and the messages.
  const dePatterns = [
    [/^lid open at ([\d.]+) s; the radio is not on by t_max = ([\d.]+) s$/, 'Deckel offen bei $1 s; das Radio ist bis t_max = $2 s nicht an'],
    [/^lid open at ([\d.]+) s$/, 'Deckel offen bei $1 s'],
    [/^seesaw vertical at ([\d.]+) s, after the lid opened at ([\d.]+) s; the radio is not on$/,
      'Wippe senkrecht bei $1 s, nachdem der Deckel sich bei $2 s geöffnet hat; das Radio ist nicht an'],
    [/^seesaw vertical at ([\d.]+) s with the sandbag (\S+) m out; the lid never opens \(it is at ([-\d.]+) deg\)$/,
      'Wippe senkrecht bei $1 s, der Sandsack $2 m weit draußen; der Deckel öffnet nie (er steht bei $3°)'],
    [/^sandbag reaches the pivot at ([\d.]+) s; the lid has not opened \(it is at ([-\d.]+) deg\)$/,
      'Sandsack erreicht die Achse bei $1 s; der Deckel hat sich nicht geöffnet (er steht bei $2°)'],
    [/^linkage locked at ([\d.]+) s: the straight rope is in line with the lid or the seesaw's arm; the lid is at ([-\d.]+) deg$/,
      'Gestänge blockiert bei $1 s: das gestreckte Seil liegt in einer Linie mit dem Deckel oder dem Arm der Wippe; der Deckel steht bei $2°'],
    [/^radio on at t = ([\d.]+) s$/, 'Radio an bei t = $1 s'],
    [/^the balloon's string is straight at ([\d.]+) s but pulls less than radio\.switch_force: the radio stays off$/,
      'die Ballonschnur ist bei $1 s gestreckt, zieht aber schwächer als radio.switch_force: das Radio bleibt aus'],
    [/^no outcome by t_max = ([\d.]+) s: the lid is at ([-\d.]+) deg$/, 'kein Ergebnis bis t_max = $1 s: der Deckel steht bei $2°'],
    [/^stopped after (\d+) events at ([\d.]+) s$/, 'angehalten nach $1 Ereignissen bei $2 s'],
    [/^M1: sandbag falling, rope slack$/, 'M1: Sandsack fällt, Seil locker'],
    [/^M2: sandbag falling, rope taut$/, 'M2: Sandsack fällt, Seil straff'],
    [/^M3: sandbag on the seesaw, rope slack$/, 'M3: Sandsack auf der Wippe, Seil locker'],
    [/^M4: sandbag on the seesaw, rope pulls the lid$/, 'M4: Sandsack auf der Wippe, Seil zieht den Deckel'],
    [/^M5: rope taut, lid resting$/, 'M5: Seil straff, Deckel liegt auf'],
    [/^seesaw vertical at ([\d.]+) s without the sandbag \(it is (\S+) m from the pivot\); the lid never opens \(it is at ([-\d.]+) deg\)$/,
      'Wippe senkrecht bei $1 s ohne den Sandsack (er ist $2 m von der Achse entfernt); der Deckel öffnet nie (er steht bei $3°)'],
    // The built machine's modes: their parts, each in German.
    [/^(M\d): ((?:sandbag|seesaw|rope|lid)[a-z ,]*)$/, (m, mode, parts) => `${mode}: ${parts.split(', ').map((p) => deModeParts[p] || p).join(', ')}`],
    [/^([a-z_]+) at ([\d.]+) s$/, (m, type, t) => `${deEvents[type.replace(/_/g, ' ')] || type} bei ${t} s`],
  ];

  // The library's messages (src/io/reader.hpp, build_scenario.cpp, build_extensions.cpp,
  // set_input.cpp, keys.cpp, toml_input.cpp, inp_input.cpp; src/core's SimulationErrors; the
  // worker's own), each without the place it names in front ("--set KEY=VALUE: ", "a.toml:3: ",
  // sentence() splits that off). Keys, numbers, units and the values given stay as they are; a
  // value given in quotes gets German quotes.
  const q = (text) => text.replace(/^'(.*)'$/, '„$1“');
  const oder = (list) => list.replace(/ or /g, ' oder ');
  const deMessages = [
    // reader.hpp: the rules every number obeys.
    [/^(\S+) must be a finite number \(given (.*)\)$/, '$1 muss eine endliche Zahl sein (gegeben: $2)'],
    [/^(\S+) must be < 0 m: the sandbag starts left of the pivot, above the left arm \(given (.*)\)$/,
      '$1 muss < 0 m sein: der Sandsack beginnt links der Achse, über dem linken Arm (gegeben: $2)'],
    [/^(\S+) must be > 0 and below (\S+) \((.*)\) so that the balloon rises \(given (.*)\)$/,
      '$1 muss > 0 und kleiner als $2 ($3) sein, damit der Ballon steigt (gegeben: $4)'],
    [/^(\S+) must be > 0 and at least mass \* com_offset\^2 = (\S+) kg m\^2 \(given (.*)\)$/,
      '$1 muss > 0 und mindestens Masse * com_offset^2 = $2 kg m^2 sein (gegeben: $3)'],
    [/^(\S+) must be ([<>]=?) (\S+)( [^(]+)? \(given (.*)\)$/, (m, k, op, x, unit, given) => `${k} muss ${op} ${x}${unit || ''} sein (gegeben: ${given})`],
    [/^(\S+) must be in ([[(]\S+, \S+[\])])( [^(]+)? \(given (.*)\)$/, (m, k, range, unit, given) => `${k} muss in ${range}${unit || ''} liegen (gegeben: ${given})`],
    [/^(\S+) must be within (\[\S+, \S+\])( [^,]+)?, the range the model is made for \(given (.*)\)$/,
      (m, k, range, unit, given) => `${k} muss in ${range}${unit || ''} liegen, dem Bereich, für den das Modell gemacht ist (gegeben: ${given})`],
    [/^(\S+) must hold finite numbers \(given (.*)\)$/, '$1 muss endliche Zahlen enthalten (gegeben: $2)'],
    [/^(\S+) must hold numbers within (\[\S+, \S+\]) m, the range the model is made for \(given (.*)\)$/,
      '$1 muss Zahlen in $2 m enthalten, dem Bereich, für den das Modell gemacht ist (gegeben: $3)'],
    // The value's form (set_input.cpp, toml_input.cpp).
    [/^(\S+) must be a number in plain units \(given (.*)\)$/, (m, k, given) => `${k} muss eine Zahl ohne Einheit sein (gegeben: ${q(given)})`],
    [/^(\S+) must be a number in (.+) \(given (.*)\)$/, (m, k, unit, given) => `${k} muss eine Zahl in ${unit} sein (gegeben: ${q(given)})`],
    [/^(\S+) must be a number \(given (.*)\)$/, (m, k, given) => `${k} muss eine Zahl sein (gegeben: ${q(given)})`],
    [/^(\S+) must be a pair of numbers \[dx, dh\] in (.+) \(given (.*)\)$/, (m, k, unit, given) => `${k} muss ein Zahlenpaar [dx, dh] in ${unit} sein (gegeben: ${q(given)})`],
    [/^(\S+) must be true or false \(given (.*)\)$/, (m, k, given) => `${k} muss true oder false sein (gegeben: ${q(given)})`],
    [/^(\S+) must be a text value, one of: (.*) \(given (.*)\)$/,
      (m, k, help, given) => `${k} muss ein Text sein, einer von: ${deKeys[k] ? deKeys[k][1] : oder(help)} (gegeben: ${q(given)})`],
    [/^(\S+) must be ([\w-]+(?:, [\w-]+)* or [\w-]+) \(given (.*)\)$/, (m, k, list, given) => `${k} muss ${oder(list)} sein (gegeben: ${q(given)})`],
    [/^KEY=VALUE must be one line without control characters$/, 'SCHLÜSSEL=WERT muss eine Zeile ohne Steuerzeichen sein'],
    [/^expected KEY=VALUE \(no key before '='\)$/, 'erwartet: SCHLÜSSEL=WERT (kein Schlüssel vor „=“)'],
    [/^expected KEY=VALUE$/, 'erwartet: SCHLÜSSEL=WERT'],
    [/^give a value after '='$/, 'nach „=“ einen Wert angeben'],
    [/^key (\S+): is not a single number$/, 'Schlüssel $1: ist keine einzelne Zahl'],
    [/^unknown key '(.*)' \(did you mean '(.*)'\?\)$/, 'unbekannter Schlüssel „$1“ (gemeint: „$2“?)'],
    [/^unknown key '(.*)'$/, 'unbekannter Schlüssel „$1“'],
    [/^unknown section \[(.*)\] \(did you mean \[(.*)\]\?\)$/, 'unbekannter Abschnitt [$1] (gemeint: [$2]?)'],
    [/^unknown section \[(.*)\]$/, 'unbekannter Abschnitt [$1]'],
    [/^key "(.*)" is quoted, so its dot does not make a section: write (\S+) = \.\.\. without the quotes, or the name after the dot under \[(.*)\]$/,
      'der Schlüssel "$1" steht in Anführungszeichen, so bildet sein Punkt keinen Abschnitt: $2 = ... ohne Anführungszeichen schreiben, oder den Namen nach dem Punkt unter [$3]'],
    [/^not valid TOML: (.*)$/, (m, why) => `kein gültiges TOML${tomlWhy(why)}`],
    // build_scenario.cpp: the rules of a machine.
    [/^(\S+) must be on the lid, at most its length 2 r_L = (\S+) m from the hinge \(given (\S+) m\)$/,
      '$1 muss auf dem Deckel liegen, höchstens seine Länge 2 r_L = $2 m vom Scharnier entfernt (gegeben: $3 m)'],
    [/^(\S+) and (\S+) both given: use one form$/, '$1 und $2 sind beide angegeben: nur eine Form verwenden'],
    [/^(\S+) must put the hinge at least (\S+) m from the pivot \(given (.*)\)$/,
      '$1 muss das Scharnier mindestens $2 m von der Achse entfernt setzen (gegeben: $3)'],
    [/^(\S+) gives the free balloon an acceleration of (\S+) g; at most (\S+) g is within the range the model is made for \(given (.*)\)$/,
      '$1 gibt dem freien Ballon eine Beschleunigung von $2 g; höchstens $3 g liegen im Bereich, für den das Modell gemacht ist (gegeben: $4)'],
    [/^(\S+) gives (\S+) (steps|rows) up to (\S+) = (\S+) s; at most (\S+) are allowed \(given (.*)\)$/,
      (m, k, n, what, tk, t, most, given) => `${k} ergibt ${n} ${what === 'steps' ? 'Schritte' : 'Zeilen'} bis ${tk} = ${t} s; höchstens ${most} sind erlaubt (gegeben: ${given})`],
    [/^(\S+) is longer than the (\S+) s in which (\S+) = (\S+) N m s\/rad stops the part it damps: the fixed step is unstable \(use a shorter step or the adaptive integrator; given (.*)\)$/,
      '$1 ist länger als die $2 s, in denen $3 = $4 N m s/rad das gedämpfte Teil anhält: der feste Schritt ist instabil (einen kürzeren Schritt oder den Integrator adaptive nehmen; gegeben: $5)'],
    [/^(\S+) puts the sandbag under the seesaw's left arm, which is at (\S+) m there \(given (.*)\)$/,
      '$1 setzt den Sandsack unter den linken Arm der Wippe, der dort auf $2 m liegt (gegeben: $3)'],
    [/^(\S+) is shorter than the distance from the seesaw's end to the lid's edge at the start \((.*)\)$/,
      '$1 ist kürzer als der Abstand vom Ende der Wippe zur Deckelkante am Anfang ($2)'],
    [/^(\S+) puts the lid above the rope, which is straight at the start \((\S+) = (\S+) m at (\S+) = (\S+) deg\) and would run under the hinge, through the box \(given (.*)\)$/,
      '$1 setzt den Deckel über das Seil, das am Anfang gestreckt ist ($2 = $3 m bei $4 = $5 deg) und unter dem Scharnier durch die Kiste liefe (gegeben: $6)'],
    [/^(\S+) can never be straight: the seesaw's end and the lid's edge are never more than (\S+) m apart \(given (.*)\)$/,
      '$1 kann nie gestreckt sein: Ende der Wippe und Deckelkante sind nie mehr als $2 m voneinander entfernt (gegeben: $3)'],
    // build_extensions.cpp: the extensions' rules.
    [/^(\S+) makes the seesaw \(a uniform bar of (\S+) = (\S+) kg from -(\S+) to r_H\) an inertia of (\S+) kg m\^2 about the pivot; at most (\S+) kg m\^2 is within the range the model is made for \(given (.*)\)$/,
      '$1 gibt der Wippe (einem gleichmäßigen Balken mit $2 = $3 kg von -$4 bis r_H) ein Trägheitsmoment von $5 kg m^2 um die Achse; höchstens $6 kg m^2 liegen im Bereich, für den das Modell gemacht ist (gegeben: $7)'],
    [/^(\S+) is too far from the pivot for the bar's inertia (\S+) kg m\^2 \(mass \* com_offset\^2 = (\S+) kg m\^2 is more\): give (\S+) too \(given (.*)\)$/,
      '$1 liegt zu weit von der Achse für das Trägheitsmoment $2 kg m^2 des Balkens (Masse * com_offset^2 = $3 kg m^2 ist mehr): auch $4 angeben (gegeben: $5)'],
    [/^(\S+) is false but other radio keys are given: remove them or enable the radio$/,
      '$1 ist false, aber andere Schlüssel des Radios sind angegeben: sie entfernen oder das Radio einschalten'],
    [/^(\S+) must be below the lift (\S+) kg \(displaced air minus helium\) so that the balloon rises \(given (.*)\)$/,
      '$1 muss unter dem Auftrieb von $2 kg liegen (verdrängte Luft minus Helium), damit der Ballon steigt (gegeben: $3)'],
    [/^(\S+) is false but (\S+) is given: remove one$/, '$1 ist false, aber $2 ist angegeben: eines von beiden entfernen'],
    [/^(\S+) needs (\S+) \(a uniform bar\) or both (\S+) and (\S+)$/, '$1 braucht $2 (ein gleichmäßiger Balken) oder sowohl $3 als auch $4'],
    [/^(\S+) needs (\S+) \(the seesaw's weight acts at its centre of mass\)$/, '$1 braucht $2 (das Gewicht der Wippe greift in ihrem Schwerpunkt an)'],
    [/^(\S+) needs a seesaw with inertia: give (\S+) \(and (\S+)\) too$/, '$1 braucht eine Wippe mit Trägheit: auch $2 (und $3) angeben'],
    [/^(\S+) is shorter than the sandbag's start on the arm \((.*)\)$/, '$1 ist kürzer als der Weg bis zum Anfangsort des Sandsacks auf dem Arm ($2)'],
    // The built machine's end stop and floor.
    [/^(\S+) needs (\S+) \(an endless arm has no end for the stop\)$/, '$1 braucht $2 (ein endloser Arm hat kein Ende für den Anschlag)'],
    [/^(\S+) needs (\S+) \(an endless arm would reach the floor at any angle\)$/, '$1 braucht $2 (ein endloser Arm reichte bei jedem Winkel bis zum Boden)'],
    [/^(\S+) needs the floor below the pivot: the box's bottom is (\S+) m above it \(hinge height minus the box's edge 2 r_L\)$/,
      '$1 braucht den Boden unter der Achse: die Unterseite der Kiste liegt $2 m darüber (Höhe des Scharniers minus die Kante der Kiste 2 r_L)'],
    [/^(\S+) puts the seesaw's (left|right) end (\S+) m below the floor \((\S+); the floor is (\S+) m below the pivot\)$/,
      (m, k, side, d, flag, floor) => `${k} setzt das ${side === 'left' ? 'linke' : 'rechte'} Ende der Wippe ${d} m unter den Boden (${flag}; der Boden liegt ${floor} m unter der Achse)`],
    [/^(\S+) is below the floor \((\S+) m < (\S+) m; (\S+)\)$/, '$1 liegt unter dem Boden ($2 m < $3 m; $4)'],
    // Restitution.
    [/^(\S+) needs (\S+) \(there is no stop to bounce off\)$/, '$1 braucht $2 (es gibt keinen Anschlag zum Zurückfedern)'],
    [/^(\S+) bounces the rope law's jerk; it cannot go with (\S+) = (\S+) \(given (\S+)\)$/,
      '$1 lässt den Ruck des Seilgesetzes zurückfedern; das geht nicht mit $2 = $3 (angegeben $4)'],
    [/^(\S+) is already straight at the start: the balloon is (\S+) m from the switch \(given (.*)\)$/,
      '$1 ist schon am Anfang gestreckt: der Ballon ist $2 m vom Schalter entfernt (gegeben: $3)'],
    // inp_input.cpp: the paper's whatnext.inp.
    [/^expected a number for (\S+) \((\S+)\), got '(.*)'( \(a decimal comma\? write a point\))?$/,
      (m, name, k, got, comma) => `erwartet: eine Zahl für ${name} (${k}), gefunden: „${got}“${comma ? ' (ein Dezimalkomma? Einen Punkt schreiben)' : ''}`],
    [/^a whatnext\.inp needs 15 numbers, one per line; found (\d+) \(next: (.*)\)$/,
      'eine whatnext.inp braucht 15 Zahlen, eine pro Zeile; gefunden: $1 (als nächste fehlt: $2)'],
    [/^a whatnext\.inp holds exactly 15 numbers; this line is one too many \('(.*)'\)$/,
      'eine whatnext.inp enthält genau 15 Zahlen; diese Zeile ist eine zu viel („$1“)'],
    // src/core: a run that cannot go on.
    [/^(.+?) at t = (\S+) s in mode (M\d)( \(degenerate contact\))?$/,
      (m, what, t, mode, degenerate) => `${deFailures[what] || what} bei t = ${t} s in Phase ${mode}${degenerate ? ' (entarteter Kontakt)' : ''}`],
    [/^no consistent set of contacts at the start \(degenerate contact\)$/, 'keine widerspruchsfreie Menge von Kontakten am Anfang (entarteter Kontakt)'],
    // The page's worker (worker.js, app.js).
    // Without the browser's reason, which is English whatever the page's language.
    [/^the WebAssembly module failed \((.*)\)$/, 'das WebAssembly-Modul ist ausgefallen'],
    [/^no function (\S+)$/, 'keine Funktion $1'],
  ];
  const deFailures = {
    'the state turned non-finite': 'der Zustand wurde unendlich oder undefiniert',
    'the motion turned non-finite': 'die Bewegung wurde unendlich oder undefiniert',
    'the integrator used its budget of 5e6 steps (loosen run.tolerance or shorten run.t_max)':
      'der Integrator hat seine 5e6 Schritte verbraucht (run.tolerance lockern oder run.t_max kürzen)',
    "the run stopped advancing (the same instant's contacts decided again and again; a fixed step may be too long for this machine)":
      'der Lauf kam nicht mehr voran (die Kontakte desselben Augenblicks wurden wieder und wieder entschieden; ein fester Schritt ist für diese Maschine vielleicht zu lang)',
    'no consistent impact': 'kein widerspruchsfreier Stoß',
    'no consistent set of contacts': 'keine widerspruchsfreie Menge von Kontakten',
  };
  // The TOML reader's (toml++) own words: "Error while parsing <what>: <detail>". The common
  // details in German; one it does not know is left out (the place, line and column, stays).
  const deTomlScopes = {
    'key-value pair': 'eines Schlüssel-Wert-Paars', array: 'einer Liste', 'inline table': 'einer Inline-Tabelle',
    'table header': 'eines Tabellenkopfs', string: 'eines Texts', 'literal string': 'eines Texts', key: 'eines Schlüssels',
    value: 'eines Werts', boolean: 'eines Wahrheitswerts', 'floating-point': 'einer Gleitkommazahl',
    'hexadecimal floating-point': 'einer Gleitkommazahl', 'decimal integer': 'einer ganzen Zahl', 'binary integer': 'einer ganzen Zahl',
    'octal integer': 'einer ganzen Zahl', 'hexadecimal integer': 'einer ganzen Zahl', date: 'eines Datums', time: 'einer Uhrzeit',
    'date-time': 'einer Zeitangabe', 'date-time offset': 'einer Zeitangabe', comment: 'eines Kommentars', 'root table': 'der Datei',
    'unicode scalar sequence': 'eines Unicode-Zeichens',
  };
  const deTomlThings = {
    value: 'ein Wert', 'value-terminator': 'das Ende des Werts', 'space or tab': 'ein Leerzeichen oder Tab',
    'decimal digit': 'eine Ziffer', digit: 'eine Ziffer', 'hex digit': 'eine Hexadezimalziffer', 'hexadecimal digit': 'eine Hexadezimalziffer',
    'exponent digit': 'eine Ziffer des Exponenten', 'exponent digit or sign': 'eine Ziffer oder ein Vorzeichen des Exponenten',
    'bare key character': 'ein Zeichen eines Schlüssels', 'bare key starting character or string delimiter': 'ein Schlüssel',
    'key or table header': 'ein Schlüssel oder Tabellenkopf', 'key-value pair': 'ein Schlüssel-Wert-Paar',
  };
  const deTomlDetails = [
    [/^encountered end-of-file$/, 'das Dateiende kam zu früh'],
    [/^expected (.+?), saw (.+)$/, (m, a, b) => (deTomlThings[a] || /^'.*'$/.test(a) ? `erwartet: ${deTomlThings[a] || q(a)}, gefunden: ${q(b)}` : null)],
    [/^cannot redefine existing ([\w -]+) '(.*)'$/, (m, what, name) => `„${name}“ ist schon festgelegt`],
    [/^could not determine value type$/, 'die Art des Werts ist nicht zu erkennen'],
    [/^leading zeroes are prohibited$/, 'führende Nullen sind nicht erlaubt'],
    [/^unexpected control character$/, 'ein Steuerzeichen an unerwarteter Stelle'],
    [/^underscores (may only follow|must be followed by) digits$/, 'ein Unterstrich nur zwischen Ziffern'],
    [/^values may not begin with underscores$/, 'ein Wert darf nicht mit einem Unterstrich beginnen'],
    [/^missing exponent$/, 'der Exponent fehlt'],
  ];
  function tomlWhy(why) {
    const m = /^Error while parsing (.+?): (.*)$/.exec(why);
    const scope = m && deTomlScopes[m[1]] ? ` beim Lesen ${deTomlScopes[m[1]]}` : '';
    const detail = m ? m[2] : why;
    for (const [re, out] of deTomlDetails) {
      const found = re.exec(detail);
      if (!found) continue;
      const words = typeof out === 'function' ? out(...found) : detail.replace(re, out);
      return words ? `${scope}: ${words}` : scope;
    }
    return scope;
  }
  // Where a message comes from, in the language's words ("whatnext.inp line 3 (ms)").
  const dePlace = (where) => where.replace(/ line (\d+)/, ' Zeile $1');
  const deEvents = {
    'sandbag lands': 'Sandsack landet', 'rope taut': 'Seil straff', 'rope slack': 'Seil locker', 'lid rests': 'Deckel liegt auf',
    'lid lifts': 'Deckel hebt ab', 'balloon caught': 'Ballon gefangen', 'balloon free': 'Ballon frei',
    'sandbag falls off': 'Sandsack fällt herunter', 'sandbag leaves': 'Sandsack hebt ab', 'lid open': 'Deckel offen',
    'seesaw vertical': 'Wippe senkrecht', 'sandbag at pivot': 'Sandsack an der Achse', 'rope locked': 'Gestänge blockiert',
    'radio on': 'Radio an', timeout: 'Zeit abgelaufen', 'event limit': 'Ereignisgrenze',
    'sandbag at stop': 'Sandsack am Anschlag', 'sandbag leaves stop': 'Sandsack verlässt den Anschlag',
    'seesaw on floor': 'Wippe auf dem Boden', 'seesaw lifts': 'Wippe hebt ab', 'sandbag on floor': 'Sandsack auf dem Boden',
    'sandbag bounces': 'Sandsack prallt ab', 'switch stays off': 'Schalter bleibt aus',
    'balloon escapes': 'Ballon entweicht', 'sandbag sticks': 'Sandsack haftet', 'sandbag slips': 'Sandsack rutscht',
    'seesaw sticks': 'Wippe haftet', 'seesaw slips': 'Wippe dreht sich wieder', 'lid sticks': 'Deckel haftet', 'lid slips': 'Deckel dreht sich wieder',
  };

  const deModeParts = {
    'sandbag falling': 'Sandsack fällt', 'sandbag on the seesaw': 'Sandsack auf der Wippe', 'sandbag at the stop': 'Sandsack am Anschlag',
    'sandbag on the floor': 'Sandsack auf dem Boden', 'seesaw on the floor': 'Wippe auf dem Boden', 'rope slack': 'Seil locker',
    'rope taut': 'Seil straff', 'rope pulls the lid': 'Seil zieht den Deckel', 'lid resting': 'Deckel liegt auf', 'rope let go': 'Seil losgelassen',
  };

  // The map and the phase plots (map.js, phase.js).
  Object.assign(de, {
    'Map: which machines work': 'Karte: welche Maschinen gehen',
    'Many machines around the one shown, two keys varied: each cell is one machine run to its end.':
      'Viele Maschinen um die gezeigte herum, zwei Größen verändert: jede Zelle ist eine Maschine, bis zu ihrem Ende gerechnet.',
    'Point at a cell to read it, click it (or Enter) to load that machine.': 'Auf eine Zelle zeigen, um sie zu lesen; klicken (oder Enter), um diese Maschine zu laden.',
    'Tap a cell to read it, tap it again to load that machine.': 'Eine Zelle antippen, um sie zu lesen; noch einmal antippen, um diese Maschine zu laden.',
    across: 'waagrecht', up: 'senkrecht', from: 'von', to: 'bis', steps: 'Schritte', colour: 'Farbe',
    'Draw the map': 'Karte zeichnen', Stop: 'Anhalten',
    "Download the map's CSV": 'CSV der Karte herunterladen',
    "The map's machines as whatnext sweep writes them": 'Die Maschinen der Karte, wie whatnext sweep sie schreibt',
    'the outcome': 'der Ausgang', "the outcome's time": 'die Zeit des Ausgangs', 'the time of: {event}': 'die Zeit von: {event}',
    'Starting…': 'Starte…', 'Stopping…': 'Halte an…', 'Stopped before the first machine.': 'Vor der ersten Maschine angehalten.',
    '{size} machines in {s} s on {workers} workers.': '{size} Maschinen in {s} s auf {workers} Workern.',
    'Stopped: {done} of {size} machines in {s} s.': 'Angehalten: {done} von {size} Maschinen in {s} s.',
    '{done} of {size} machines': '{done} von {size} Maschinen',
    'the WebAssembly module failed ({message})': 'das WebAssembly-Modul ist ausgefallen ({message})',
    'Steps of {key}: a whole number from 1 to {max}, not "{given}".': 'Schritte von {key}: eine ganze Zahl von 1 bis {max}, nicht „{given}“.',
    'The map needs two different keys (both are {key}).': 'Die Karte braucht zwei verschiedene Größen (beide sind {key}).',
    'did not happen': 'kam nicht vor', 'invalid machine': 'ungültige Maschine', 'the run failed': 'der Lauf scheiterte',
    '⊕ the machine shown': '⊕ die gezeigte Maschine', 'not run yet': 'noch nicht gerechnet', '{event} at {t} s': '{event} bei {t} s',
    'Outcome of each machine: {y} down, {x} across': 'Ausgang jeder Maschine: {y} senkrecht, {x} waagrecht',
    invalid: 'ungültig', failed: 'gescheitert', never: 'nie',
    'The table holds maps of up to {most} machines; the CSV holds every one.': 'Die Tabelle fasst Karten bis {most} Maschinen; die CSV-Datei enthält alle.',
    'The map (arrow keys move between machines, Enter loads one; the table below says the same)':
      'Die Karte (Pfeiltasten wandern zwischen den Maschinen, Enter lädt eine; die Tabelle darunter sagt dasselbe)',
    'The same map on the command line': 'Dieselbe Karte auf der Kommandozeile', 'The map as a table': 'Die Karte als Tabelle',
    'Any variable against any other': 'Jede Größe gegen jede andere',
    'φL against φS': 'φL gegen φS', 'r against its rate': 'r gegen seine Rate', 'the lid: angle against its rate': 'der Deckel: Winkel gegen seine Rate',
    'the energy by part against time': 'die Energie jedes Teils gegen die Zeit', 'the energy of each part': 'die Energie jedes Teils', 'Plots to start from': 'Fertige Diagramme',
    events: 'Ereignisse', 'energy [J]': 'Energie [J]', 'Events marked (rings): {list}.': 'Markierte Ereignisse (Ringe): {list}.',
    'This map is of the machine before the last change (other keys or another machine): a cell loads its own machine; Draw the map again for the machine shown.':
      'Diese Karte gehört zur Maschine vor der letzten Änderung (andere Werte oder eine andere Maschine): eine Zelle lädt ihre eigene Maschine; „Karte zeichnen“ zeichnet sie für die gezeigte Maschine neu.',
    'The columns of': 'Die Spalten von', 'Drag to zoom in, double-click to zoom out.': 'Ziehen vergrößert, Doppelklick verkleinert.',
  });

  const kLanguages = {
    en: { name: 'English', table: {}, keys: {}, patterns: [], messages: [], place: (w) => w, events: {}, decimal: '.', html: 'en' },
    de: { name: 'Deutsch', table: de, keys: deKeys, patterns: dePatterns, messages: deMessages, place: dePlace, events: deEvents,
          decimal: ',', html: 'de' },
  };

  // The page's language: the link's lang=, else the one chosen before, else the browser's.
  function pick() {
    const fromLink = new URLSearchParams(location.hash.slice(1)).get('lang');
    if (fromLink && kLanguages[fromLink]) return fromLink;
    try {
      const saved = localStorage.getItem('whatnext.lang');
      if (saved && kLanguages[saved]) return saved;
    } catch (e) { /* storage off (a file:// page in some browsers): the browser's language */ }
    for (const l of navigator.languages || [navigator.language || 'en']) {
      const code = String(l).slice(0, 2).toLowerCase();
      if (kLanguages[code]) return code;
    }
    return 'en';
  }

  let lang = pick();
  const L = () => kLanguages[lang];
  const fill = (text, args) => text.replace(/\{(\w+)\}/g, (m, k) => (args && k in args ? String(args[k]) : m));
  // Words of the page: t('English {x}', {x}).
  const t = (english, args) => fill(L().table[english] ?? english, args);
  // Numbers with the language's decimal sign (in sentences: a point between digits).
  // A pair or interval of numbers is split by a semicolon where the comma is the decimal sign
  // ("[0,001; 1000]", not "[0,001, 1000]").
  const decimals = (text) => (L().decimal === '.' ? text
    : text.replace(/([[(])([-+\d.eE]+|dx), ([-+\d.eE]+|dh)([\])])/g, '$1$2; $3$4').replace(/(\d)\.(\d)/g, `$1${L().decimal}$2`));
  // A sentence of the library (an outcome, a mode, a message): its pattern's translation, numbers
  // with the decimal sign. A message may name where it comes from first ("a.toml:3: ", "--set
  // KEY=VALUE: "): that place is kept (in the language's words) and the rest translated.
  function translated(text) {
    for (const [re, out] of [...L().patterns, ...L().messages]) if (re.test(text)) return text.replace(re, out);
    return null;
  }
  function sentence(text) {
    const whole = translated(text);
    if (whole !== null) return decimals(whole);
    for (let i = text.indexOf(': '); i >= 0; i = text.indexOf(': ', i + 1)) {
      const rest = translated(text.slice(i + 2));
      if (rest !== null) return `${L().place(text.slice(0, i))}: ${decimals(rest)}`;
    }
    return decimals(text);
  }
  // An event's words ("rope taut (impact, 0.08 J -> 0.07 J)").
  function eventWords(text) {
    const ev = L().events;
    return decimals(text.replace(/^([a-z ]+?)( \(impact|$)/, (m, name, rest) => (ev[name] || name) + (rest ? (lang === 'en' ? ' (impact' : ' (Stoß') : '')));
  }

  // index.html's own words: every text and title, aria-label and placeholder.
  function translatePage(root) {
    document.documentElement.lang = L().html;
    if (lang === 'en') return;
    const walker = document.createTreeWalker(root, NodeFilter.SHOW_TEXT);
    const nodes = [];
    while (walker.nextNode()) nodes.push(walker.currentNode);
    for (const node of nodes) {
      if (node.parentElement.closest('script, style, pre, code, #timeline tbody')) continue;
      const text = node.nodeValue.replace(/\s+/g, ' ').trim();
      if (text && L().table[text] !== undefined) node.nodeValue = node.nodeValue.replace(node.nodeValue.trim(), L().table[text]);
    }
    for (const el of root.querySelectorAll('[title], [aria-label], [placeholder]')) {
      for (const a of ['title', 'aria-label', 'placeholder']) {
        const v = el.getAttribute(a);
        if (v && L().table[v] !== undefined) el.setAttribute(a, L().table[v]);
      }
    }
    const title = L().table[document.title];
    if (title) document.title = title;
  }

  window.whatnextStrings = {
    t, sentence, eventWords, decimals, translatePage,
    keyName: (key, english) => (L().keys[key] ? L().keys[key][0] : english),
    keyHelp: (key, english) => (L().keys[key] ? L().keys[key][1] : english),
    get lang() { return lang; },
    get decimal() { return L().decimal; },  // the decimal sign of the page's numbers
    languages: Object.fromEntries(Object.entries(kLanguages).map(([k, v]) => [k, v.name])),
    set(code) {
      if (!kLanguages[code]) return;
      lang = code;
      try { localStorage.setItem('whatnext.lang', code); } catch (e) { /* not kept */ }
    },
  };
})();
