import { AnimationMixer } from 'three';

// Plays every animation in a glTF file on one clock the page owns. odeskin's export animates bone
// transforms and morph weights in separate channels that must stay in step; keeping the clock here
// (instead of letting the mixer advance and wrap it) lets the slider set any time, the end included.
export class Playback {
  constructor(root, clips) {
    this.mixer = new AnimationMixer(root);
    this.actions = clips.map((clip) => this.mixer.clipAction(clip).play());
    this.duration = clips.reduce((longest, clip) => Math.max(longest, clip.duration), 0);
    this.playing = false;
    this.seek(0);
  }

  get animated() {
    return this.duration > 0;
  }

  // Shows the pose at `seconds` (clamped to the clip). A zero-step mixer update evaluates every
  // track at the actions' time without advancing or looping it.
  seek(seconds) {
    this.time = Math.min(Math.max(seconds, 0), this.duration);
    for (const action of this.actions) action.time = this.time;
    this.mixer.update(0);
  }

  // Moves the clock on by `seconds` while playing, wrapping to the start at the end.
  advance(seconds) {
    if (!this.playing || !this.animated) return;
    this.seek((this.time + seconds) % this.duration);
  }

  dispose() {
    this.mixer.stopAllAction();
    this.mixer.uncacheRoot(this.mixer.getRoot());
  }
}
