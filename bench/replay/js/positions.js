// SPDX-License-Identifier: MIT
// Reads an engine's positions as the page stores them (bench/output/position_stream.h has
// the byte layout): base64 text of varint records, one state after another, each body's centre
// a whole number of quanta from its initial centre, only the bodies that changed written.

function decodeBase64(text) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

// Varints of up to 2^53 (offsets stay below 2^51), read with arithmetic: JavaScript's bit
// operators work on 32 bits.
class VarintReader {
  constructor(bytes) {
    this.bytes = bytes;
    this.at = 0;
  }

  done() {
    return this.at >= this.bytes.length;
  }

  next() {
    let value = 0;
    let scale = 1;
    for (;;) {
      if (this.at >= this.bytes.length) throw new Error("position stream cut short");
      const b = this.bytes[this.at++];
      value += (b & 0x7f) * scale;
      if (b < 0x80) return value;
      scale *= 128;
    }
  }

  signed() {
    const z = this.next();
    return z % 2 === 1 ? -(z + 1) / 2 : z / 2;
  }
}

// Calls visit(state, body, dx, dy, lost) for every record, in order; returns the number of
// states, state 0 (every body as built, not in the stream) included.
function readStream(bytes, bodies, visit) {
  const reader = new VarintReader(bytes);
  let state = 0;
  while (!reader.done()) {
    state++;
    const records = reader.next();
    let next = 0;
    for (let r = 0; r < records; r++) {
      const head = reader.next();
      const body = next + Math.floor(head / 2);
      if (body >= bodies) throw new Error("position stream names body " + body);
      if (head % 2 === 1) {
        visit(state, body, 0, 0, true);
      } else {
        visit(state, body, reader.signed(), reader.signed(), false);
      }
      next = body + 1;
    }
  }
  return state + 1;
}

// An engine's stored states: `movers` (the bodies that ever leave their initial centre, in scene
// order), `slot[body]` (its index among them, or -1) and `offsets`, per state and mover the
// offset in quanta as x, y (NaN while the body is lost).
function decodeTrack(base64, bodies) {
  const bytes = decodeBase64(base64);
  const slot = new Int32Array(bodies).fill(-1);
  const movers = [];
  const states = readStream(bytes, bodies, (state, body) => {
    if (slot[body] < 0) {
      slot[body] = 0;
      movers.push(body);
    }
  });
  movers.sort((a, b) => a - b);
  movers.forEach((body, m) => { slot[body] = m; });
  const width = movers.length * 2;
  const offsets = new Float64Array(states * width);
  const current = new Float64Array(width);  // the offsets of the state being read
  let complete = 1;  // states copied into `offsets` (state 0 is all zero)
  const copyUpTo = (state) => {
    for (; complete < state; complete++) offsets.set(current, complete * width);
  };
  readStream(bytes, bodies, (state, body, dx, dy, lost) => {
    copyUpTo(state);  // the records of earlier states are all applied
    const at = slot[body] * 2;
    if (lost) {
      current[at] = current[at + 1] = NaN;
    } else {
      current[at] = (Number.isNaN(current[at]) ? 0 : current[at]) + dx;
      current[at + 1] = (Number.isNaN(current[at + 1]) ? 0 : current[at + 1]) + dy;
    }
  });
  copyUpTo(states);
  return { movers: movers, slot: slot, offsets: offsets, states: states };
}
