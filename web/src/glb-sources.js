// The three ways a file reaches the page: ?src=URL (links and tests), the Open button, and
// dropping a file anywhere on the window. Each calls onFile(File) or onUrl(url).
export function watchGlbSources({ onFile, onUrl }) {
  const input = document.getElementById('file');
  input.addEventListener('change', () => {
    if (input.files.length > 0) onFile(input.files[0]);
    input.value = ''; // choosing the same file again still loads it
  });

  // Without preventDefault on dragover the browser would open the dropped file itself.
  window.addEventListener('dragover', (event) => {
    event.preventDefault();
    document.body.classList.add('dragging');
  });
  window.addEventListener('dragleave', (event) => {
    if (event.relatedTarget === null) document.body.classList.remove('dragging');
  });
  window.addEventListener('drop', (event) => {
    event.preventDefault();
    document.body.classList.remove('dragging');
    const file = event.dataTransfer.files[0];
    if (file !== undefined) onFile(file);
  });

  const src = new URLSearchParams(window.location.search).get('src');
  if (src) onUrl(src);
}
