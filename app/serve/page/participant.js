// An experiment participant's page (app/experiment/web_participant.hpp). The session serves one
// phase at a time on this port (ready, trial, questionnaire), each from a server of its own: the
// page polls /scene.json and follows the phase's id. In a trial the pointer moves the hand (every
// web finger together) in the plane facing the camera, the wheel closes and opens the grip (each
// finger along the task's grip direction), W and S move the hand nearer and away. The page shows
// no condition: the server sends none.
const TLX = [
  ["mental_demand", "Mental demand", "How mentally demanding was the task?", "Very low", "Very high"],
  ["physical_demand", "Physical demand", "How physically demanding was the task?", "Very low", "Very high"],
  ["temporal_demand", "Temporal demand", "How hurried or rushed was the pace of the task?", "Very low", "Very high"],
  ["performance", "Performance", "How successful were you in accomplishing what you were asked to do?", "Perfect", "Failure"],
  ["effort", "Effort", "How hard did you have to work to accomplish your level of performance?", "Very low", "Very high"],
  ["frustration", "Frustration", "How insecure, discouraged, irritated, stressed and annoyed were you?", "Very low", "Very high"],
];
const GRIP_STEP_M = 0.001, GRIP_MIN_M = -0.02, GRIP_MAX_M = 0.03, DEPTH_STEP_M = 0.005;
const hand = gf.hand = {fingers: [], anchor: null, offsets: [], grip: 0, drag: null, timer: null, last: 0};
const panel = gf.panel = {phase: null, id: null, submitted: false, lastSeen: 0};

function panelBox(...children) {
  const box = $("#panel");
  box.replaceChildren(...children);
  return box;
}

function trialLine(p) {
  return "Trial " + p.trial + " of " + p.trials + " · block " + p.block + " of " + p.blocks + (p.practice ? " · practice" : "");
}

function resultLine(previous) {
  if (!previous) return element("div", "", "result");
  const done = previous.ran && previous.success;
  const text = done ? "Last trial: done in " + previous.completion_s.toFixed(2) + " s"
                    : "Last trial: not done" + (previous.failure ? " (" + previous.failure + ")" : "");
  return element("div", text, "result " + (done ? "ok" : "no"));
}

// Ready: the task, the trial, the last result; Start counts down 3, 2, 1, then asks for the trial.
function showReady(p) {
  $("#frame").hidden = true;
  const start = element("button", "Start");
  start.id = "start";
  const count = element("div", "", "count");
  start.addEventListener("click", () => {
    start.disabled = true;
    let n = 3;
    const tick = () => {
      if (n === 0) {
        count.textContent = "Go";
        command("ready").then(a => { if (!a.startsWith("ok")) { start.disabled = false; count.textContent = a; } },
                              () => {});  // the phase ends as it answers: the next one shows
        return;
      }
      count.textContent = String(n--);
      setTimeout(tick, 600);
    };
    tick();
  });
  const how = p.device === "udp" ? "Use your haptic device; watch the picture here."
                                  : "Drag to move your hand, the wheel closes and opens your grip, W and S move it nearer and away.";
  panelBox(element("h2", trialLine(p)), element("div", p.instruction, "instruction"), resultLine(p.previous),
           element("div", "You have " + p.time_limit_s.toFixed(1) + " s. " + how), start, count);
}

// A trial: the frames, the instruction and the time left; the hand starts where the fingers are.
function showTrial(p) {
  const img = $("#frame");
  img.hidden = false;
  img.src = withToken("stream.mjpg?phase=" + encodeURIComponent(p.id));
  hand.fingers = gf.scene.fingers.filter(f => f.device === "web").map(f => f.name);
  hand.anchor = null;
  hand.drag = null;
  hand.grip = 0;
  const left = element("div", "", "count");
  left.id = "time-left";
  panelBox(element("h2", trialLine(p)), element("div", p.instruction, "instruction"), left);
}

// The questionnaire after a block: Raw NASA-TLX's six scales (0..100 in steps of 5) and realism.
function showQuestionnaire(p) {
  $("#frame").hidden = true;
  panel.submitted = false;
  const form = element("form");
  form.id = "questionnaire";
  for (const [key, title, question, low, high] of TLX) {
    const scale = element("div", undefined, "scale"), input = document.createElement("input"), value = element("b", "50");
    Object.assign(input, {type: "range", min: 0, max: 100, step: 5, value: 50, name: key});
    input.addEventListener("input", () => { value.textContent = input.value; input.dataset.touched = "1"; });
    const ends = element("div", undefined, "ends");
    ends.append(element("span", low), element("span", high));
    scale.append(element("div", title + ": " + question + " "), input, ends);
    scale.firstChild.appendChild(value);
    form.appendChild(scale);
  }
  const likert = element("div", undefined, "likert");
  for (let v = 1; v <= 7; ++v) {
    const label = element("label"), radio = document.createElement("input");
    Object.assign(radio, {type: "radio", name: "realism", value: v});
    label.append(radio, String(v));
    likert.appendChild(label);
  }
  const ends = element("div", undefined, "ends");
  ends.append(element("span", "not at all"), element("span", "just like real objects"));
  form.append(element("div", "Realism: how much did touching the objects feel like touching real objects?"), likert, ends);
  const message = element("div", "", "result no"), submit = element("button", "Submit");
  submit.type = "submit";
  form.append(submit, message);
  form.addEventListener("submit", async e => {
    e.preventDefault();
    const untouched = TLX.filter(([key]) => !form.elements[key].dataset.touched).map(([, title]) => title);
    if (untouched.length) { message.textContent = "Please answer every scale (not yet: " + untouched.join(", ") + ")."; return; }
    const realism = form.querySelector("input[name=realism]:checked");
    if (!realism) { message.textContent = "Please rate the realism (1 to 7)."; return; }
    const line = "answers " + TLX.map(([key]) => key + "=" + form.elements[key].value).join(" ") + " realism=" + realism.value;
    let answer = "";
    try { answer = await command(line); } catch (err) {
      // No answer: not saved, or saved as the phase ended. If saved, the next phase replaces
      // this form in a moment; if not, the form stays and can be sent again.
      message.textContent = "Not saved yet: the session did not answer. Press Submit again if this stays.";
      return;
    }
    if (!answer.startsWith("ok")) { message.textContent = answer; return; }
    panel.submitted = true;
    panelBox(element("h2", p.last ? "Thank you: the session is over." : "Thank you."),
             element("div", p.last ? "You may close this page." : "The next block starts in a moment."));
  });
  panelBox(element("h2", "Block " + p.block + " of " + p.blocks + " is over"),
           element("div", "Please rate the block you have just done."), form);
}

function enterPhase(scene) {
  gf.scene = scene;
  const p = scene.participant;
  panel.phase = p.phase;
  panel.id = p.id;
  $("#scene").textContent = "Experiment · " + p.participant;
  $("#mode").textContent = "";
  if (p.phase === "ready") showReady(p);
  else if (p.phase === "trial") showTrial(p);
  else if (p.phase === "questionnaire") showQuestionnaire(p);
}

// Every web finger's device target: the hand's anchor, each finger's offset, the grip.
function handTargets() {
  const grip = gf.scene.participant.grip || {};
  return hand.fingers.map((name, i) => {
    const g = grip[name] || [0, 0, 0];
    return [0, 1, 2].map(k => hand.anchor[k] + hand.offsets[i][k] + hand.grip * g[k]);
  });
}

// At most one round of moves every 30 ms (the devices go there in 30 ms); the last of a burst
// goes out when its 30 ms are up.
function sendHand() {
  if (!hand.anchor || panel.phase !== "trial") return;
  const wait = 30 - (performance.now() - hand.last);
  if (wait > 0) { if (!hand.timer) hand.timer = setTimeout(() => { hand.timer = null; sendHand(); }, wait); return; }
  hand.last = performance.now();
  handTargets().forEach((p, i) => command("move " + hand.fingers[i] + " " + p.map(v => v.toFixed(5)).join(" ") + " 0.03"));
}

function startHand(s) {
  if (hand.anchor || !s.fingers) return;
  const devices = hand.fingers.map(name => s.fingers.find(f => f.name === name).device);
  if (!devices.length) return;
  hand.anchor = devices[0].slice();
  hand.offsets = devices.map(d => sub(d, devices[0]));
}

function attachHand() {
  const img = $("#frame");
  img.addEventListener("pointerdown", e => {
    if (!hand.anchor || panel.phase !== "trial") return;
    e.preventDefault();
    img.setPointerCapture(e.pointerId);
    const b = basis(), depth = dot(sub(hand.anchor, b.eye), b.f);
    hand.drag = {depth, from: unproject(e.clientX, e.clientY, depth), anchor: hand.anchor.slice()};
  });
  img.addEventListener("pointermove", e => {
    if (!hand.drag) return;
    const to = unproject(e.clientX, e.clientY, hand.drag.depth);
    hand.anchor = [0, 1, 2].map(k => hand.drag.anchor[k] + to[k] - hand.drag.from[k]);
    sendHand();
  });
  const release = () => { hand.drag = null; };
  img.addEventListener("pointerup", release);
  img.addEventListener("pointercancel", release);
  img.addEventListener("wheel", e => {
    e.preventDefault();
    if (!hand.anchor) return;
    hand.grip = Math.min(GRIP_MAX_M, Math.max(GRIP_MIN_M, hand.grip + (e.deltaY < 0 ? GRIP_STEP_M : -GRIP_STEP_M)));
    sendHand();
  }, {passive: false});
  document.addEventListener("keydown", e => {
    if (!hand.anchor || hand.drag || (e.key !== "w" && e.key !== "W" && e.key !== "s" && e.key !== "S")) return;
    const f = basis().f, step = e.key === "w" || e.key === "W" ? -DEPTH_STEP_M : DEPTH_STEP_M;  // W nearer, as on the full page
    hand.anchor = hand.anchor.map((v, k) => v + step * f[k]);
    sendHand();
  });
}

async function participantPoll() {
  let scene = null;
  try { scene = await (await fetch(withToken("scene.json"), {cache: "no-store"})).json(); } catch (e) { scene = null; }
  if (scene && scene.participant && scene.participant.id !== panel.id) enterPhase(scene);
  if (!scene && !(panel.phase === "questionnaire" && panel.submitted)) {
    $("#status").textContent = panel.phase === "trial" ? "the trial is over: its result comes next" : "waiting for the session…";
  } else $("#status").textContent = "";
  if (scene && panel.phase === "trial") {
    try {
      const s = await (await fetch(withToken("state.json"), {cache: "no-store"})).json();
      if (s.fingers) {
        gf.state = s;
        startHand(s);
        const left = Math.max(0, scene.participant.time_limit_s - s.t);
        $("#time-left").textContent = left.toFixed(1) + " s left";
      }
    } catch (e) { /* the trial ended: the next poll finds the next phase */ }
  }
  setTimeout(participantPoll, 100);
}

function participantStart() {
  document.body.classList.add("participant");
  $("#panel").hidden = false;
  attachHand();
  enterPhase(gf.scene);
  participantPoll();
}
