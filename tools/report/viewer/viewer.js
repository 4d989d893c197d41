/* posekit report viewer.
 *
 * Embedded by the C++ report writer into one self-contained HTML file, after
 * three.js r111 and its OrbitControls. Reads the JSON in
 * <script id="posekit-report-data"> (schema 1) and builds the whole page.
 * Test hooks: body[data-status] = loading | ready | no-webgl | unsupported |
 * error, body[data-errors] = number of errors so far, #frame=K opens frame K.
 */
(function () {
  'use strict';

  const SCHEMA_VERSION = 1;
  const FPS = 12;
  const POSE_CACHE_LIMIT = 400;        // ~120 KB per 10k-vertex pose
  const BASE_GREY = [0xc9 / 255, 0xcc / 255, 0xd1 / 255];
  const MARKER_COLOUR = 0xff9900;      // orange: never "red" for the pixel tests
  const POINT_COLOUR = 0x0b5d63;       // dark teal
  const BACKGROUND = 0xffffff;
  const PLOT_COLOURS = ['#1f77b4', '#2ca02c', '#ff7f0e', '#9467bd', '#17becf',
    '#8c564b', '#bcbd22', '#e377c2', '#7f7f7f', '#393b79'];
  // viridis sampled at 9 even stops; no stop is red-ish
  const VIRIDIS = [[68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142],
    [33, 144, 141], [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37]];
  const VIEW_DIRECTION = [0.35, 0.3, 1];   // initial camera direction from the target
  const PLOT_HEIGHT = 96;

  const body = document.body;
  let errorCount = 0;
  let errorList = null;

  // ---------------------------------------------------------------- errors

  function setStatus(status) {
    body.dataset.status = status;
  }

  function errorText(value) {
    if (value instanceof Error) return value.message || String(value);
    if (typeof value === 'string') return value;
    try { return JSON.stringify(value); } catch (e) { return String(value); }
  }

  // Every error is counted in data-errors and listed in a visible box.
  function noteError(value) {
    errorCount += 1;
    body.dataset.errors = String(errorCount);
    if (!errorList) {
      const box = el('div', 'pk-errors');
      box.setAttribute('role', 'alert');
      el('strong', null, 'Errors in the report viewer', box);
      errorList = el('ul', null, null, box);
      body.insertBefore(box, body.firstChild);
    }
    if (errorList.childNodes.length < 20) el('li', null, errorText(value), errorList);
  }

  function installErrorHooks() {
    window.addEventListener('error', function (event) {
      noteError(event.error || event.message || 'unknown error');
    });
    window.addEventListener('unhandledrejection', function (event) {
      noteError(event.reason || 'unhandled promise rejection');
    });
    const originalError = console.error;
    console.error = function () {
      const args = Array.prototype.slice.call(arguments);
      noteError(args.map(errorText).join(' '));
      return originalError.apply(console, args);
    };
  }

  // ---------------------------------------------------------------- helpers

  function el(tag, className, text, parent) {
    const node = document.createElement(tag);
    if (className) node.className = className;
    if (text !== null && text !== undefined) node.textContent = String(text);
    if (parent) parent.appendChild(node);
    return node;
  }

  function button(label, title, parent, onClick) {
    const node = el('button', 'pk-button', label, parent);
    node.type = 'button';
    if (title) node.title = title;
    node.addEventListener('click', onClick);
    return node;
  }

  const LITTLE_ENDIAN = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

  function bytesFromBase64(text) {
    const bin = atob(text || '');
    const out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
    return out;
  }

  // Little-endian unsigned integers of 1, 2 or 4 bytes from base64.
  function decodeUint(text, width) {
    const bytes = bytesFromBase64(text);
    if (width === 1) return bytes;
    const n = Math.floor(bytes.length / width);
    const Type = width === 2 ? Uint16Array : Uint32Array;
    if (LITTLE_ENDIAN) return new Type(bytes.buffer, 0, n);
    const view = new DataView(bytes.buffer);
    const out = new Type(n);
    for (let i = 0; i < n; i++) out[i] = width === 2 ? view.getUint16(2 * i, true) : view.getUint32(4 * i, true);
    return out;
  }

  // Quantized Uint16 triples to model coordinates.
  function dequantize(q, origin, step) {
    const n = q.length - (q.length % 3);
    const out = new Float32Array(n);
    for (let i = 0; i < n; i += 3) {
      out[i] = origin[0] + q[i] * step[0];
      out[i + 1] = origin[1] + q[i + 1] * step[1];
      out[i + 2] = origin[2] + q[i + 2] * step[2];
    }
    return out;
  }

  function formatNumber(value) {
    if (!isFinite(value)) return String(value);
    if (value === 0) return '0';
    return String(parseFloat(value.toPrecision(3)));
  }

  // "of the diagonal" values are fractions: show them as percentages.
  function formatValue(value, unit, withUnit) {
    if (unit === 'of the diagonal') return formatNumber(value * 100) + '%' + (withUnit ? ' of the diagonal' : '');
    return formatNumber(value) + (withUnit && unit ? ' ' + unit : '');
  }

  // Any CSS colour to [r, g, b] in 0..1, via the 2D canvas parser.
  const colourParser = document.createElement('canvas').getContext('2d');
  function parseColour(text) {
    colourParser.fillStyle = '#000000';
    colourParser.fillStyle = String(text || '');
    const css = colourParser.fillStyle;
    let m = /^#([0-9a-f]{2})([0-9a-f]{2})([0-9a-f]{2})$/i.exec(css);
    if (m) return [parseInt(m[1], 16) / 255, parseInt(m[2], 16) / 255, parseInt(m[3], 16) / 255];
    m = /^rgba?\(([\d.]+),\s*([\d.]+),\s*([\d.]+)/.exec(css);
    if (m) return [m[1] / 255, m[2] / 255, m[3] / 255];
    return [0, 0, 0];
  }

  function buildViridisTable() {
    const lut = new Float32Array(256 * 3);
    const last = VIRIDIS.length - 1;
    for (let i = 0; i < 256; i++) {
      const t = (i / 255) * last;
      const k = Math.min(Math.floor(t), last - 1);
      const f = t - k;
      for (let c = 0; c < 3; c++) lut[3 * i + c] = (VIRIDIS[k][c] * (1 - f) + VIRIDIS[k + 1][c] * f) / 255;
    }
    return lut;
  }

  function viridisGradientCss() {
    const stops = VIRIDIS.map(function (c, i) {
      return 'rgb(' + c.join(',') + ') ' + ((100 * i) / (VIRIDIS.length - 1)).toFixed(1) + '%';
    });
    return 'linear-gradient(to right, ' + stops.join(', ') + ')';
  }

  // ---------------------------------------------------------------- data

  function readReport() {
    const node = document.getElementById('posekit-report-data');
    if (!node) throw new Error('the report data (#posekit-report-data) is missing');
    try {
      return JSON.parse(node.textContent);
    } catch (e) {
      throw new Error('the report data is not valid JSON: ' + e.message);
    }
  }

  function validate(data) {
    const mesh = data.mesh;
    if (!mesh || !(mesh.vertex_count > 0) || !(mesh.face_count > 0)) throw new Error('the report has no mesh');
    if (!Array.isArray(mesh.origin) || !Array.isArray(mesh.step)) throw new Error('the mesh has no quantization');
    if (!Array.isArray(data.poses) || data.poses.length === 0) throw new Error('the report has no poses');
    if (!Array.isArray(data.panels) || data.panels.length === 0) throw new Error('the report has no panels');
    data.panels.forEach(function (panel, i) {
      if (!Array.isArray(panel.frames) || panel.frames.length === 0) throw new Error('panel ' + i + ' has no frames');
    });
  }

  function frameCount(data) {
    const names = data.frames && Array.isArray(data.frames.names) ? data.frames.names : [];
    let count = names.length;
    data.panels.forEach(function (panel) { count = Math.max(count, panel.frames.length); });
    return Math.max(1, count);
  }

  // Decoded poses, least recently used dropped first: decoding every pose
  // of a long sequence upfront would be too slow.
  function makePoseCache(data) {
    const cache = new Map();
    const mesh = data.mesh;
    return function getPose(index) {
      let pose = cache.get(index);
      if (pose) {
        cache.delete(index);
        cache.set(index, pose);
        return pose;
      }
      if (typeof data.poses[index] !== 'string') throw new Error('pose ' + index + ' is missing');
      pose = dequantize(decodeUint(data.poses[index], 2), mesh.origin, mesh.step);
      if (pose.length < mesh.vertex_count * 3) throw new Error('pose ' + index + ' has too few vertices');
      cache.set(index, pose);
      if (cache.size > POSE_CACHE_LIMIT) cache.delete(cache.keys().next().value);
      return pose;
    };
  }

  function decodeFaces(mesh) {
    const faces = decodeUint(mesh.faces, mesh.index_bytes === 2 ? 2 : 4);
    if (faces.length < mesh.face_count * 3) throw new Error('the mesh has too few face indices');
    for (let i = 0; i < mesh.face_count * 3; i++) {
      if (faces[i] >= mesh.vertex_count) throw new Error('face ' + Math.floor(i / 3) + ' has an index out of range');
    }
    return faces;
  }

  // ---------------------------------------------------------------- page

  function buildHeader(data) {
    const header = el('header', 'pk-header', null, body);
    const titleBar = el('div', 'pk-titlebar', null, header);
    el('h1', 'pk-title', data.title || 'posekit report', titleBar);
    if (data.job) el('span', 'pk-job', data.job, titleBar);
    if (data.command) el('code', 'pk-command', data.command, header);
    if (Array.isArray(data.summary) && data.summary.length) {
      const list = el('dl', 'pk-summary', null, header);
      data.summary.forEach(function (item) {
        const row = el('div', 'pk-summary-item', null, list);
        el('dt', null, item.label, row);
        el('dd', null, item.value, row);
      });
    }
  }

  function buildLegends(panels, parent) {
    const seen = new Map();
    panels.forEach(function (panel) {
      const map = panel.colour_map;
      if (map && isFinite(map.max) && !seen.has(map.label)) seen.set(map.label, map);
    });
    seen.forEach(function (map) {
      const legend = el('div', 'pk-legend', null, parent);
      el('div', 'pk-legend-label', map.label || 'value', legend);
      const scale = el('div', 'pk-legend-scale', null, legend);
      el('div', 'pk-legend-bar', null, scale).style.background = viridisGradientCss();
      el('span', null, null, scale);
      const ticks = el('div', 'pk-legend-ticks', null, scale);
      [0, 0.5, 1].forEach(function (f) {
        el('span', 'pk-tick pk-tick-' + Math.round(f * 2), formatValue(map.max * f, map.unit, false), ticks);
      });
      // The unit follows the max tick ("2.1% of the diagonal") outside the bar.
      const full = formatValue(map.max, map.unit, true);
      const last = formatValue(map.max, map.unit, false);
      el('span', 'pk-legend-unit', full.slice(last.length), scale);
    });
  }

  function buildTables(tables) {
    if (!Array.isArray(tables) || tables.length === 0) return;
    const section = el('section', 'pk-tables', null, body);
    tables.forEach(function (spec) {
      const table = el('table', 'pk-table', null, section);
      if (spec.title) el('caption', null, spec.title, table);
      if (Array.isArray(spec.columns)) {
        const row = el('tr', null, null, el('thead', null, null, table));
        spec.columns.forEach(function (c) { el('th', null, c, row); });
      }
      const tbody = el('tbody', null, null, table);
      (spec.rows || []).forEach(function (cells) {
        const row = el('tr', null, null, tbody);
        (cells || []).forEach(function (c) { el('td', null, c, row); });
      });
    });
  }

  function showMessage(view, text) {
    el('div', 'pk-message', text, view);
  }

  function createGlContext(canvas) {
    const attributes = { alpha: false, depth: true, stencil: false, antialias: true,
      premultipliedAlpha: true, preserveDrawingBuffer: true, powerPreference: 'default' };
    try {
      return canvas.getContext('webgl', attributes) || canvas.getContext('experimental-webgl', attributes);
    } catch (e) {
      return null;
    }
  }

  // Columns for n panels that give the largest square-ish cell.
  function chooseGrid(n, width, height) {
    let best = { cols: 1, rows: n, size: -1 };
    for (let cols = 1; cols <= n; cols++) {
      const rows = Math.ceil(n / cols);
      const size = Math.min(width / cols, height / rows);
      if (size > best.size + 0.5) best = { cols: cols, rows: rows, size: size };
    }
    return best;
  }

  // ---------------------------------------------------------------- viewer

  function main() {
    setStatus('loading');
    const data = readReport();
    if (!data || data.posekit_report !== SCHEMA_VERSION) {
      buildHeader({ title: (data && data.title) || 'posekit report' });
      const view = el('div', 'pk-view pk-view-message', null, body);
      showMessage(view, 'This report has schema version ' + (data ? data.posekit_report : 'unknown') +
        '; this viewer reads version ' + SCHEMA_VERSION + ' only.');
      setStatus('unsupported');
      return;
    }
    validate(data);
    if (data.title) document.title = data.title;

    const F = frameCount(data);
    const frameNames = (data.frames && data.frames.names) || [];
    const regionsByFrame = (data.frames && data.frames.regions) || [];
    const anyRegions = regionsByFrame.some(function (r) { return Array.isArray(r) && r.length > 0; });
    const plots = F > 1 && Array.isArray(data.plots) ? data.plots.filter(function (p) { return Array.isArray(p.values); }) : [];

    // ---- DOM skeleton
    buildHeader(data);
    const toolbar = el('div', 'pk-toolbar', null, body);
    const view = el('div', 'pk-view', null, body);
    // Regions float over the view's top right corner: no extra row above it.
    const regionsRow = anyRegions ? el('div', 'pk-regions', null, view) : null;
    const plotBlock = plots.length ? el('div', 'pk-plots', null, body) : null;

    const canvas = el('canvas', 'pk-canvas', null, view);
    const gl = createGlContext(canvas);
    if (!gl || typeof THREE === 'undefined') {
      if (gl) noteError('three.js is missing from this report');
      if (plotBlock) body.removeChild(plotBlock);
      view.classList.add('pk-view-message');
      showMessage(view, !gl ? 'WebGL is not available in this browser, so the meshes cannot be shown.'
        : 'three.js is missing from this report.');
      buildTables(data.tables);
      setStatus(gl ? 'error' : 'no-webgl');
      return;
    }

    // ---- three.js state
    const mesh = data.mesh;
    const N = mesh.vertex_count;
    const M = mesh.face_count;
    const diagonal = mesh.diagonal > 0 ? mesh.diagonal : 1;
    const faces = decodeFaces(mesh);
    const getPose = makePoseCache(data);
    const viridis = buildViridisTable();

    const renderer = new THREE.WebGLRenderer({ canvas: canvas, context: gl, antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    renderer.setClearColor(BACKGROUND, 1);
    const scene = new THREE.Scene();
    const camera = new THREE.PerspectiveCamera(35, 1, diagonal * 1e-3, diagonal * 100);
    // Lights ride on the camera so the lit side follows the view.
    scene.add(camera);
    camera.add(new THREE.AmbientLight(0xffffff, 0.62));
    const headLight = new THREE.DirectionalLight(0xffffff, 0.5);
    headLight.position.set(0.5, 0.7, 0);
    camera.add(headLight);
    camera.add(headLight.target);
    headLight.target.position.set(0, 0, -1);

    const controls = new THREE.OrbitControls(camera, canvas);
    controls.screenSpacePanning = true;
    canvas.tabIndex = 0;

    const meshMaterial = new THREE.MeshLambertMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide });
    const markerGeometry = new THREE.SphereBufferGeometry(0.008 * diagonal, 16, 12);
    const markerMaterial = new THREE.MeshLambertMaterial({ color: MARKER_COLOUR });
    const pointSize = 0.004 * diagonal;
    const pointsMaterial = new THREE.PointsMaterial({ color: POINT_COLOUR, size: pointSize, sizeAttenuation: true });

    const grid = { cols: 1, rows: 1, cellW: 1, cellH: 1, width: 1, height: 1 };
    const panels = data.panels.map(createPanel);
    let frame = 0;
    let renderPending = false;
    // Until the person moves the view, a new layout (the page settling, a resize) frames the mesh again.
    let viewMoved = false;
    let viewFramed = false;
    let playTimer = null;
    let slider = null;
    let frameLabel = null;
    let playButton = null;
    let plotCanvas = null;
    const plotValueEls = [];

    function createPanel(spec) {
      const geometry = new THREE.BufferGeometry();
      const position = new THREE.BufferAttribute(new Float32Array(M * 9), 3).setUsage(THREE.DynamicDrawUsage);
      const colour = new THREE.BufferAttribute(new Float32Array(M * 9), 3).setUsage(THREE.DynamicDrawUsage);
      geometry.setAttribute('position', position);
      geometry.setAttribute('color', colour);
      const surface = new THREE.Mesh(geometry, meshMaterial);
      surface.frustumCulled = false;    // positions change per frame; the cached bounds would go stale
      const group = new THREE.Group();
      group.add(surface);
      const markers = new THREE.Group();
      group.add(markers);
      scene.add(group);
      const cell = el('div', 'pk-cell', null, view);
      const label = el('div', 'pk-cell-label', null, cell);
      el('div', 'pk-cell-title', spec.title || '', label);
      const sets = el('div', 'pk-cell-sets', null, label);
      return { spec: spec, group: group, geometry: geometry, position: position, colour: colour,
        markers: markers, markerList: [], points: null, cell: cell, setsEl: sets,
        shown: { pose: -1, scalar: null, sets: null, markers: null, points: null, init: false } };
    }

    function panelFrame(panel, k) {
      const frames = panel.spec.frames;
      return frames[Math.min(k, frames.length - 1)] || {};
    }

    // Expand the indexed pose into per-face corners (so faces can differ in colour).
    function fillPositions(panel, pose) {
      const out = panel.position.array;
      for (let f = 0, o = 0; f < M; f++) {
        for (let c = 0; c < 3; c++, o += 3) {
          const v = 3 * faces[3 * f + c];
          out[o] = pose[v];
          out[o + 1] = pose[v + 1];
          out[o + 2] = pose[v + 2];
        }
      }
      panel.position.needsUpdate = true;
      panel.geometry.computeVertexNormals();   // flat: corners are not shared
    }

    function fillColours(panel, fr) {
      const out = panel.colour.array;
      const scalar = typeof fr.scalar === 'string' ? decodeUint(fr.scalar, 1) : null;
      const useScalar = scalar && scalar.length >= N;
      for (let f = 0, o = 0; f < M; f++) {
        for (let c = 0; c < 3; c++, o += 3) {
          if (useScalar) {
            const s = 3 * scalar[faces[3 * f + c]];
            out[o] = viridis[s]; out[o + 1] = viridis[s + 1]; out[o + 2] = viridis[s + 2];
          } else {
            out[o] = BASE_GREY[0]; out[o + 1] = BASE_GREY[1]; out[o + 2] = BASE_GREY[2];
          }
        }
      }
      // Face sets override the scalar on all three corners.
      (fr.face_sets || []).forEach(function (set) {
        const rgb = parseColour(set.colour);
        const list = decodeUint(set.faces, 4);
        for (let i = 0; i < list.length; i++) {
          const f = list[i];
          if (f >= M) continue;
          for (let o = 9 * f; o < 9 * f + 9; o += 3) {
            out[o] = rgb[0]; out[o + 1] = rgb[1]; out[o + 2] = rgb[2];
          }
        }
      });
      panel.colour.needsUpdate = true;
    }

    function fillSetLabels(panel, fr) {
      panel.setsEl.textContent = '';
      (fr.face_sets || []).forEach(function (set) {
        const row = el('div', 'pk-cell-set', null, panel.setsEl);
        const rgb = parseColour(set.colour);
        // A swatch only for non-red colours: red pixels are reserved for red faces.
        if (!(rgb[0] > 150 / 255 && rgb[1] < 80 / 255 && rgb[2] < 80 / 255)) {
          el('span', 'pk-set-swatch', null, row).style.background =
            'rgb(' + rgb.map(function (c) { return Math.round(c * 255); }).join(',') + ')';
        }
        el('span', null, set.label || 'face set', row);
      });
    }

    function fillMarkers(panel, list) {
      while (panel.markers.children.length) panel.markers.remove(panel.markers.children[0]);
      panel.markerList = [];
      (list || []).forEach(function (marker) {
        if (!Array.isArray(marker.position)) return;
        const sphere = new THREE.Mesh(markerGeometry, markerMaterial);
        sphere.position.fromArray(marker.position);
        panel.markers.add(sphere);
        panel.markerList.push({ position: sphere.position, label: marker.label || '' });
      });
    }

    function fillPoints(panel, encoded) {
      if (panel.points) {
        panel.group.remove(panel.points);
        panel.points.geometry.dispose();
        panel.points = null;
      }
      if (typeof encoded !== 'string' || !encoded) return;
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(dequantize(decodeUint(encoded, 2), mesh.origin, mesh.step), 3));
      panel.points = new THREE.Points(geometry, pointsMaterial);
      panel.group.add(panel.points);
    }

    // Swap in what changed since the panel's last frame.
    function showPanelFrame(panel, k) {
      const fr = panelFrame(panel, k);
      const shown = panel.shown;
      if (fr.pose !== shown.pose) {
        fillPositions(panel, getPose(fr.pose));
        shown.pose = fr.pose;
      }
      if (!shown.init || fr.scalar !== shown.scalar || fr.face_sets !== shown.sets) {
        fillColours(panel, fr);
        fillSetLabels(panel, fr);
        shown.scalar = fr.scalar;
        shown.sets = fr.face_sets;
      }
      if (!shown.init || fr.markers !== shown.markers) {
        fillMarkers(panel, fr.markers);
        shown.markers = fr.markers;
      }
      if (!shown.init || fr.points !== shown.points) {
        fillPoints(panel, fr.points);
        shown.points = fr.points;
      }
      shown.init = true;
    }

    function setFrame(k) {
      frame = Math.max(0, Math.min(F - 1, k | 0));
      // A broken panel frame is reported and skipped; the others still show.
      panels.forEach(function (panel) {
        try { showPanelFrame(panel, frame); } catch (e) { noteError(e); }
      });
      body.dataset.frame = String(frame);
      if (frameLabel) frameLabel.textContent = (frameNames[frame] || 'frame') + ' \u00b7 frame ' + frame + ' / ' + (F - 1);
      updateRegions();
      updatePlotValues();
      drawPlot();
      requestRender();
    }

    // Every frame change goes through the slider, as the hash does.
    function seek(k) {
      if (!slider) return;
      slider.value = String(((k % F) + F) % F);
      slider.dispatchEvent(new Event('input'));
    }

    function togglePlay() {
      if (playTimer) {
        clearInterval(playTimer);
        playTimer = null;
      } else {
        playTimer = setInterval(function () { seek(frame + 1); }, 1000 / FPS);
      }
      playButton.textContent = playTimer ? 'Pause' : 'Play';
    }

    // ---- camera

    function boundingSphere() {
      const box = new THREE.Box3();
      const arrays = [];
      panels.forEach(function (panel) {
        if (panel.shown.pose >= 0) arrays.push(getPose(panel.shown.pose).subarray(0, N * 3));
        if (panel.points) arrays.push(panel.points.geometry.attributes.position.array);
      });
      const v = new THREE.Vector3();
      arrays.forEach(function (a) {
        for (let i = 0; i < a.length; i += 3) box.expandByPoint(v.set(a[i], a[i + 1], a[i + 2]));
      });
      if (box.isEmpty()) return { center: new THREE.Vector3(), radius: diagonal / 2 };
      const center = box.getCenter(new THREE.Vector3());
      let r2 = 0;
      arrays.forEach(function (a) {
        for (let i = 0; i < a.length; i += 3) r2 = Math.max(r2, center.distanceToSquared(v.set(a[i], a[i + 1], a[i + 2])));
      });
      return { center: center, radius: Math.sqrt(r2) || diagonal / 2 };
    }

    function resetView() {
      viewFramed = true;
      const sphere = boundingSphere();
      const vfov = camera.fov * Math.PI / 180;
      const hfov = 2 * Math.atan(Math.tan(vfov / 2) * camera.aspect);
      const distance = (sphere.radius / Math.sin(Math.min(vfov, hfov) / 2)) * 1.04;
      const direction = new THREE.Vector3().fromArray(VIEW_DIRECTION).normalize();
      controls.target.copy(sphere.center);
      camera.up.set(0, 1, 0);
      camera.position.copy(sphere.center).addScaledVector(direction, distance);
      controls.update();
      requestRender();
    }

    function jumpToRegion(region) {
      viewMoved = true;
      const direction = camera.position.clone().sub(controls.target);
      if (direction.lengthSq() === 0) direction.fromArray(VIEW_DIRECTION);
      direction.normalize();
      controls.target.fromArray(region.center);
      camera.position.copy(controls.target).addScaledVector(direction, 3 * Math.max(region.radius || 0, diagonal * 1e-4));
      controls.update();
      requestRender();
    }

    // Near and far planes follow the orbit distance so zooming never clips.
    function updateClipPlanes() {
      const distance = camera.position.distanceTo(controls.target);
      camera.near = Math.max(distance * 0.01, diagonal * 1e-6);
      camera.far = distance * 2 + diagonal * 10;
      camera.updateProjectionMatrix();
    }

    // ---- rendering

    function requestRender() {
      if (renderPending) return;
      renderPending = true;
      requestAnimationFrame(render);
    }

    function render() {
      renderPending = false;
      updateClipPlanes();
      // three's point scale ignores the viewport and the field of view: correct it
      // so the points are pointSize model units across.
      pointsMaterial.size = pointSize * (grid.cellH / grid.height) / Math.tan(camera.fov * Math.PI / 360);
      renderer.setScissorTest(false);
      renderer.clear();
      renderer.setScissorTest(true);
      panels.forEach(function (panel, i) {
        const x = (i % grid.cols) * grid.cellW;
        const y = grid.height - (Math.floor(i / grid.cols) + 1) * grid.cellH;
        renderer.setViewport(x, y, grid.cellW, grid.cellH);
        renderer.setScissor(x, y, grid.cellW, grid.cellH);
        panels.forEach(function (other) { other.group.visible = other === panel; });
        renderer.render(scene, camera);
      });
      renderer.setScissorTest(false);
    }

    function layout() {
      const width = Math.max(1, view.clientWidth);
      const top = view.getBoundingClientRect().top + window.pageYOffset;
      const reserve = plotBlock ? plotBlock.offsetHeight || PLOT_HEIGHT + 30 : 0;
      const height = Math.max(window.innerHeight - top - reserve - 6, Math.round(window.innerHeight * 0.55), 240);
      view.style.height = height + 'px';
      renderer.setSize(width, height);
      const g = chooseGrid(panels.length, width, height);
      grid.cols = g.cols;
      grid.rows = g.rows;
      grid.cellW = Math.floor(width / g.cols);
      grid.cellH = Math.floor(height / g.rows);
      grid.width = width;
      grid.height = height;
      panels.forEach(function (panel, i) {
        const style = panel.cell.style;
        style.left = (i % g.cols) * grid.cellW + 'px';
        style.top = Math.floor(i / g.cols) * grid.cellH + 'px';
        style.width = grid.cellW + 'px';
        style.height = grid.cellH + 'px';
      });
      camera.aspect = grid.cellW / grid.cellH;
      camera.updateProjectionMatrix();
      sizePlot();
      if (!viewMoved && viewFramed) resetView();
      requestRender();
    }

    // Tooltip with the label of the marker under the pointer, if any.
    function onCanvasHover(event) {
      const rect = canvas.getBoundingClientRect();
      const x = event.clientX - rect.left;
      const y = event.clientY - rect.top;
      const col = Math.floor(x / grid.cellW);
      const row = Math.floor(y / grid.cellH);
      const panel = col < grid.cols ? panels[row * grid.cols + col] : null;
      let best = null;
      let bestDistance = 10;   // pixels
      if (panel) {
        const p = new THREE.Vector3();
        panel.markerList.forEach(function (marker) {
          p.copy(marker.position).project(camera);
          if (p.z > 1) return;
          const px = col * grid.cellW + ((p.x + 1) / 2) * grid.cellW;
          const py = row * grid.cellH + ((1 - p.y) / 2) * grid.cellH;
          const d = Math.hypot(px - x, py - y);
          if (d < bestDistance) { best = marker; bestDistance = d; }
        });
      }
      canvas.title = best ? best.label : '';
    }

    // ---- toolbar

    button('Reset view', 'Frame the whole mesh', toolbar, function () { viewMoved = false; resetView(); });
    if (F > 1) {
      const group = el('div', 'pk-frames', null, toolbar);
      button('\u25c0', 'Previous frame', group, function () { seek(frame - 1); });
      playButton = button('Play', 'Play / pause (' + FPS + ' frames per second)', group, togglePlay);
      playButton.classList.add('pk-play');
      button('\u25b6', 'Next frame', group, function () { seek(frame + 1); });
      slider = el('input', 'pk-slider', null, group);
      slider.type = 'range';
      slider.min = '0';
      slider.max = String(F - 1);
      slider.step = '1';
      slider.value = '0';
      slider.setAttribute('aria-label', 'frame');
      slider.addEventListener('input', function () { setFrame(parseInt(slider.value, 10) || 0); });
      frameLabel = el('span', 'pk-frame-label', null, group);
    }
    buildLegends(data.panels, toolbar);
    el('div', 'pk-hint', 'drag: orbit \u00b7 right-drag or shift-drag: pan \u00b7 wheel: zoom', view);

    function updateRegions() {
      if (!regionsRow) return;
      regionsRow.textContent = '';
      const list = regionsByFrame[frame];
      regionsRow.hidden = !Array.isArray(list) || list.length === 0;
      if (regionsRow.hidden) return;
      el('div', 'pk-regions-label', 'Jump to region', regionsRow);
      list.forEach(function (region) {
        if (!Array.isArray(region.center)) return;
        button(region.label || 'region', 'Centre the view on this region', regionsRow, function () { jumpToRegion(region); });
      });
    }

    // ---- plots

    function buildPlots() {
      if (!plotBlock) return;
      const legend = el('ul', 'pk-plot-legend', null, plotBlock);
      plots.forEach(function (plot, i) {
        const item = el('li', null, null, legend);
        el('span', 'pk-swatch', null, item).style.background = PLOT_COLOURS[i % PLOT_COLOURS.length];
        el('span', null, plot.label || 'plot ' + (i + 1), item);
        plotValueEls.push(el('span', 'pk-plot-value', null, item));
      });
      plotCanvas = el('canvas', 'pk-plot', null, plotBlock);
      plotCanvas.style.height = PLOT_HEIGHT + 'px';
      plotCanvas.title = 'Click to go to a frame';
      const seekAt = function (event) {
        const rect = plotCanvas.getBoundingClientRect();
        const area = plotArea(rect.width, rect.height);
        const t = (event.clientX - rect.left - area.left) / Math.max(1, area.width);
        seek(Math.round(Math.max(0, Math.min(1, t)) * (F - 1)));
      };
      plotCanvas.addEventListener('mousedown', seekAt);
      plotCanvas.addEventListener('mousemove', function (event) { if (event.buttons & 1) seekAt(event); });
    }

    function plotArea(width, height) {
      return { left: 52, top: 8, width: Math.max(1, width - 64), height: Math.max(1, height - 26) };
    }

    function sizePlot() {
      if (!plotCanvas) return;
      const ratio = window.devicePixelRatio || 1;
      plotCanvas.width = Math.round(plotCanvas.clientWidth * ratio);
      plotCanvas.height = Math.round(PLOT_HEIGHT * ratio);
      drawPlot();
    }

    function updatePlotValues() {
      plots.forEach(function (plot, i) {
        const v = plot.values[frame];
        plotValueEls[i].textContent = typeof v === 'number' ? ': ' + formatNumber(v) : '';
      });
    }

    function seriesRange(values) {
      let lo = 0;
      let hi = 0;
      values.forEach(function (v) { if (isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); } });
      return { lo: lo, hi: hi > lo ? hi : lo + 1 };
    }

    // All plots on one axis unless their ranges differ a lot; then each is
    // scaled to its own range (its values are in the legend).
    function drawPlot() {
      if (!plotCanvas || !plotCanvas.width) return;
      const ratio = plotCanvas.width / Math.max(1, plotCanvas.clientWidth);
      const width = plotCanvas.clientWidth;
      const height = PLOT_HEIGHT;
      const ctx = plotCanvas.getContext('2d');
      ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
      ctx.fillStyle = '#ffffff';
      ctx.fillRect(0, 0, width, height);
      const area = plotArea(width, height);
      const ranges = plots.map(function (p) { return seriesRange(p.values); });
      const spans = ranges.map(function (r) { return r.hi - r.lo; });
      const shared = Math.max.apply(null, spans) <= 20 * Math.min.apply(null, spans);
      const common = { lo: Math.min.apply(null, ranges.map(function (r) { return r.lo; })),
        hi: Math.max.apply(null, ranges.map(function (r) { return r.hi; })) };
      const xAt = function (k) { return area.left + (F > 1 ? (k / (F - 1)) * area.width : 0); };

      ctx.strokeStyle = '#c3c9d2';
      ctx.lineWidth = 1;
      ctx.strokeRect(area.left + 0.5, area.top + 0.5, area.width, area.height);
      ctx.fillStyle = '#4a5160';
      ctx.font = '11px sans-serif';
      ctx.textAlign = 'right';
      ctx.textBaseline = 'middle';
      ctx.fillText(shared ? formatNumber(common.hi) : 'max', area.left - 4, area.top + 4);
      ctx.fillText(shared ? formatNumber(common.lo) : 'min', area.left - 4, area.top + area.height - 2);
      ctx.textBaseline = 'top';
      ctx.textAlign = 'left';
      ctx.fillText('0', area.left, area.top + area.height + 3);
      ctx.textAlign = 'right';
      ctx.fillText(String(F - 1), area.left + area.width, area.top + area.height + 3);
      ctx.textAlign = 'center';
      ctx.fillText('frame', area.left + area.width / 2, area.top + area.height + 3);

      plots.forEach(function (plot, i) {
        const r = shared ? common : ranges[i];
        ctx.strokeStyle = PLOT_COLOURS[i % PLOT_COLOURS.length];
        ctx.lineWidth = 1.5;
        ctx.beginPath();
        let drawing = false;
        for (let k = 0; k < F; k++) {
          const v = plot.values[k];
          if (!isFinite(v) || v === null) { drawing = false; continue; }
          const y = area.top + area.height - ((v - r.lo) / (r.hi - r.lo)) * area.height;
          if (drawing) ctx.lineTo(xAt(k), y); else ctx.moveTo(xAt(k), y);
          drawing = true;
        }
        ctx.stroke();
      });

      ctx.strokeStyle = '#1d2330';
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.moveTo(Math.round(xAt(frame)) + 0.5, area.top);
      ctx.lineTo(Math.round(xAt(frame)) + 0.5, area.top + area.height);
      ctx.stroke();
    }

    // ---- start

    function frameFromHash() {
      const m = /[#&]frame=(\d+)/.exec(window.location.hash || '');
      return m ? parseInt(m[1], 10) : null;
    }

    function applyHash() {
      const k = frameFromHash();
      if (k !== null && slider) seek(Math.min(k, F - 1));
    }

    buildPlots();
    buildTables(data.tables);
    controls.addEventListener('change', requestRender);
    controls.addEventListener('start', function () { viewMoved = true; });
    canvas.addEventListener('mousemove', onCanvasHover);
    window.addEventListener('resize', layout);
    window.addEventListener('hashchange', applyHash);

    layout();
    setFrame(0);
    applyHash();
    resetView();
    render();
    setStatus('ready');
  }

  // ---------------------------------------------------------------- go

  body.dataset.errors = '0';
  setStatus('loading');
  installErrorHooks();
  try {
    main();
  } catch (e) {
    noteError(e);
    const message = el('div', 'pk-fatal', 'The report could not be shown: ' + errorText(e), null);
    body.appendChild(message);
    setStatus('error');
  }
})();
