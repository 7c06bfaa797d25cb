// Average time between drawn frames over a sliding window. One frame's interval jitters too much to
// read; a window of recent frames stays current when the model or the window size changes.
export class FrameTimer {
  constructor(windowSize = 60) {
    this.windowSize = windowSize;
    this.intervals = [];
    this.sum = 0;
    this.last = null;
  }

  // Call once per drawn frame with the requestAnimationFrame timestamp (ms).
  tick(now) {
    if (this.last !== null) {
      const interval = now - this.last;
      this.intervals.push(interval);
      this.sum += interval;
      if (this.intervals.length > this.windowSize) this.sum -= this.intervals.shift();
    }
    this.last = now;
  }

  // The page draws on demand: after an idle gap the next interval is not a frame time.
  pause() {
    this.last = null;
  }

  // Milliseconds per frame, or null before two consecutive frames were drawn.
  get averageMs() {
    return this.intervals.length > 0 ? this.sum / this.intervals.length : null;
  }
}
