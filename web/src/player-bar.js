// The bar under the view: play/pause, the time slider, the clock and the frame time. It only shows
// state and reports what the user asks for; main.js decides what happens.
export class PlayerBar {
  constructor({ onTogglePlay, onSeek }) {
    this.button = document.getElementById('play');
    this.slider = document.getElementById('time');
    this.clock = document.getElementById('clock');
    this.frameTime = document.getElementById('frame-time');
    this.status = document.getElementById('status');
    this.duration = 0;

    this.button.addEventListener('click', onTogglePlay);
    this.slider.addEventListener('input', () => onSeek(Number(this.slider.value)));
    // Space plays and pauses, unless a control that uses the key itself has the focus: a button
    // (Play clicks itself), a text field. The slider has no use for it, and the hidden file input
    // keeps the focus after Open, where Space would open the file dialog again. A held key toggles
    // once.
    window.addEventListener('keydown', (event) => {
      if (event.code !== 'Space' || this.button.disabled) return;
      const target = event.target;
      if (target instanceof HTMLButtonElement) return;
      if (target instanceof HTMLInputElement && target.type !== 'range' && target.type !== 'file') return;
      event.preventDefault();
      if (!event.repeat) onTogglePlay();
    });
    // The file input activates on the key's release, which the keydown above cannot stop.
    document.getElementById('file').addEventListener('keyup', (event) => {
      if (event.code === 'Space') event.preventDefault();
    });
  }

  // duration 0: a model without animation; nothing to play.
  setDuration(seconds) {
    this.duration = seconds;
    this.slider.max = String(seconds > 0 ? seconds : 1);
    this.slider.disabled = seconds === 0;
    this.button.disabled = seconds === 0;
  }

  setPlaying(playing) {
    this.button.textContent = playing ? 'Pause' : 'Play';
    this.button.setAttribute('aria-pressed', String(playing));
  }

  setTime(seconds) {
    this.slider.value = String(seconds);
    this.clock.textContent = `${seconds.toFixed(2)} / ${this.duration.toFixed(2)} s`;
  }

  setFrameTime(ms) {
    if (ms === null) {
      this.frameTime.textContent = '– ms/frame';
      this.frameTime.title = 'Time between drawn frames, averaged';
      return;
    }
    this.frameTime.textContent = `${ms.toFixed(1)} ms/frame`;
    this.frameTime.title = `Time between drawn frames, averaged: ${(1000 / ms).toFixed(0)} fps`;
  }

  setStatus(text, isError = false) {
    this.status.textContent = text;
    this.status.title = text; // the bar shows the start; the whole message on hover
    this.status.classList.toggle('error', isError);
  }
}
