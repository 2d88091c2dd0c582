// The dataink page: a spec editor whose chart is drawn by the server as you type. Every text the
// server sends is put into the page as text (textContent), never as markup.
'use strict';

const $ = (id) => document.getElementById(id);
const DEBOUNCE_MS = 300;
const EXTENSIONS = { svg: 'svg', png: 'png', csv: 'csv', lint: 'json', sarif: 'sarif', report: 'html' };
const state = { files: new Map(), timer: null, seq: 0, preview: null };

const EXAMPLE = `# Edit the spec: the chart is drawn again as you type.
[data.decay]
values = [
  { t = 0, activity = 100.0 },
  { t = 1, activity = 61.2 },
  { t = 2, activity = 37.9 },
  { t = 3, activity = 22.8 },
  { t = 4, activity = 14.1 },
  { t = 5, activity = 8.6 },
]

[[chart]]
name = "decay"
kind = "line"
data = "decay"
title = "Activity falls by about 40% an hour"
x = { field = "t", title = "Time", unit = "h" }
y = { field = "activity", title = "Activity", unit = "%" }
markers = true
`;

/** The request body: the spec as TOML, or a form with the spec and the chosen data files. */
function body() {
  const spec = $('spec').value;
  if (state.files.size === 0) {
    return { body: spec, headers: { 'Content-Type': 'application/toml' } };
  }
  const form = new FormData();
  form.append('spec', spec);
  for (const [name, file] of state.files) form.append('file', file, name);
  return { body: form, headers: {} };
}

function post(path) {
  const { body: sent, headers } = body();
  return fetch(path, { method: 'POST', body: sent, headers });
}

function setStatus(text, error) {
  const status = $('status');
  status.textContent = text;
  status.classList.toggle('error', Boolean(error));
}

/** Line numbers beside the editor, each line with a diagnostic marked (its message as a tooltip). */
function drawGutter(diagnostics) {
  const lines = $('spec').value.split('\n').length;
  const marks = new Map();
  for (const d of diagnostics) {
    if (!d.line) continue;
    const seen = marks.get(d.line);
    if (!seen || d.severity === 'error') marks.set(d.line, d);
  }
  const gutter = $('gutter');
  gutter.replaceChildren();
  for (let n = 1; n <= lines; n++) {
    const row = document.createElement('div');
    row.textContent = String(n);
    const mark = marks.get(n);
    if (mark) {
      row.className = mark.severity;
      row.title = mark.message;
      row.dataset.line = String(n);
    }
    gutter.appendChild(row);
  }
  gutter.scrollTop = $('spec').scrollTop;
}

/** Select line `line` (1-based) of the editor. */
function goToLine(line) {
  const spec = $('spec');
  const lines = spec.value.split('\n');
  let start = 0;
  for (let i = 0; i < line - 1 && i < lines.length; i++) start += lines[i].length + 1;
  const end = start + (lines[line - 1] || '').length;
  spec.focus();
  spec.setSelectionRange(start, end);
  spec.scrollTop = Math.max(0, (line - 3) * 20);
}

function item(severity, where, message, hint) {
  const li = document.createElement('li');
  li.className = severity;
  if (where) {
    const span = document.createElement('span');
    span.className = 'where';
    span.textContent = where;
    li.appendChild(span);
  }
  li.appendChild(document.createTextNode(message));
  if (hint) {
    const small = document.createElement('span');
    small.className = 'hint';
    small.textContent = hint;
    li.appendChild(small);
  }
  return li;
}

function showDiagnostics(diagnostics) {
  const list = $('diagnostics');
  list.replaceChildren();
  for (const d of diagnostics) {
    const where = d.line ? `${d.line}:${d.column}` : '';
    const li = item(d.severity, where, `${d.severity}: ${d.message}${d.label ? ` (${d.label})` : ''}`, d.hint);
    if (d.line) {
      li.dataset.line = String(d.line);
      li.addEventListener('click', () => goToLine(d.line));
    }
    list.appendChild(li);
  }
  drawGutter(diagnostics);
}

function showFindings(lint) {
  const list = $('findings');
  list.replaceChildren();
  const findings = (lint.charts || []).flatMap((c) => c.findings || []);
  if (findings.length === 0) {
    list.appendChild(item('', '', 'No findings.', ''));
    return;
  }
  for (const f of findings) {
    const where = f.line ? `${f.line}:${f.column}` : '';
    list.appendChild(item(f.severity, where, `${f.code} ${f.rule}: ${f.message}`, f.hint));
  }
}

/** Keep the chart list in step with the spec's charts, keeping the chosen one when it stays. */
function updateCharts(names) {
  const select = $('chart');
  const chosen = select.value;
  const same = names.length === select.options.length && names.every((n, i) => select.options[i].value === n);
  if (!same) {
    select.replaceChildren();
    for (const name of names) {
      const option = document.createElement('option');
      option.value = name;
      option.textContent = name;
      select.appendChild(option);
    }
    if (names.includes(chosen)) select.value = chosen;
  }
}

function chartQuery() {
  const chart = $('chart').value;
  return chart ? `&chart=${encodeURIComponent(chart)}` : '';
}

async function problem(response) {
  try {
    return await response.json();
  } catch (e) {
    return { error: `the server answered ${response.status}` };
  }
}

/** Check the spec, then draw the chosen chart and lint it; answers to older edits are ignored. */
async function refresh() {
  const seq = ++state.seq;
  const image = $('chart-image');
  image.classList.add('stale');
  setStatus('Drawing…');
  try {
    const checked = await post('/api/check');
    if (seq !== state.seq) return;
    const answer = await problem(checked);
    showDiagnostics(answer.diagnostics || []);
    if (!checked.ok) {
      setStatus(answer.error || 'the spec has errors', true);
      return;
    }
    updateCharts(answer.charts || []);
    const query = chartQuery();
    const [svg, lint] = await Promise.all([post(`/api/render?format=svg${query}`), post(`/api/render?format=lint${query}`)]);
    if (seq !== state.seq) return;
    if (!svg.ok) {
      const failed = await problem(svg);
      showDiagnostics(failed.diagnostics || []);
      setStatus(failed.error || 'the chart could not be drawn', true);
      return;
    }
    const url = URL.createObjectURL(await svg.blob());
    if (state.preview) URL.revokeObjectURL(state.preview);
    state.preview = url;
    image.src = url;
    image.classList.remove('stale');
    if (lint.ok) showFindings(await lint.json());
    const count = $('findings').querySelectorAll('li.error, li.warning').length;
    setStatus(`Drawn ${$('chart').value}; ${count} lint finding${count === 1 ? '' : 's'}`);
  } catch (e) {
    if (seq === state.seq) setStatus(`cannot reach the server: ${e.message}`, true);
  }
}

function schedule() {
  clearTimeout(state.timer);
  state.timer = setTimeout(refresh, DEBOUNCE_MS);
  drawGutter([]);
}

async function download(format) {
  const response = await post(`/api/render?format=${format}${chartQuery()}`);
  if (!response.ok) {
    const failed = await problem(response);
    setStatus(failed.error || `the ${format} could not be made`, true);
    return;
  }
  const url = URL.createObjectURL(await response.blob());
  const a = document.createElement('a');
  const name = ['lint', 'sarif', 'report'].includes(format) ? 'spec' : $('chart').value || 'chart';
  a.href = url;
  a.download = `${name}.${EXTENSIONS[format]}`;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

function showFiles() {
  const names = [...state.files.keys()];
  $('file-list').textContent = names.length ? names.join(', ') : '';
  $('clear-files').hidden = names.length === 0;
}

function start() {
  const spec = $('spec');
  spec.value = EXAMPLE;
  spec.addEventListener('input', schedule);
  spec.addEventListener('scroll', () => { $('gutter').scrollTop = spec.scrollTop; });
  $('chart').addEventListener('change', refresh);
  $('files').addEventListener('change', (event) => {
    for (const file of event.target.files) state.files.set(file.name, file);
    showFiles();
    refresh();
  });
  $('clear-files').addEventListener('click', () => {
    state.files.clear();
    $('files').value = '';
    showFiles();
    refresh();
  });
  for (const button of document.querySelectorAll('button[data-format]')) {
    button.addEventListener('click', () => download(button.dataset.format));
  }
  drawGutter([]);
  refresh();
}

start();
