// pixelcloth's browser viewer: the scenes that `pixelcloth view` wrote, drawn with three.js (r111, Debian's
// libjs-three). Each scene is a GLB whose script twin (scenes/NNN.glb.js) calls pixelclothView.sceneLoaded, because
// a page opened from file:// may load scripts but not fetch files. Positions of later frames are the GLB's morph
// targets, applied here on the CPU so that the garment, its cage curves and markers move together.
//
// The page reports what it drew in <pre id="pixelcloth-status"> (JSON): the tests read it in headless Chromium.
// URL options: ?scene=K opens scene K; ?check=all opens every scene in turn and records each.
(function () {
  'use strict';
  var site = window.PIXELCLOTH_SITE;
  var status = { ready: false, done: false, webgl: false, errors: [], scenes: [] };
  var statusElement = document.getElementById('pixelcloth-status');
  function report() { statusElement.textContent = JSON.stringify(status); }
  function fail(message) {
    status.errors.push(String(message));
    document.getElementById('message').textContent = String(message);
    report();
  }
  window.addEventListener('error', function (e) { fail(e.message || e); });
  window.addEventListener('unhandledrejection', function (e) { fail(e.reason); });
  var consoleError = console.error;
  console.error = function () {
    fail(Array.prototype.join.call(arguments, ' '));
    consoleError.apply(console, arguments);
  };
  if (!site || !window.THREE || !THREE.GLTFLoader || !THREE.OrbitControls) {
    fail('site.js or three.js did not load');
    return;
  }

  var params = new URLSearchParams(window.location.search);
  var checkAll = params.get('check') === 'all';
  var canvas = document.getElementById('view');
  var renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
  status.webgl = !!renderer.getContext();
  var background = new THREE.Color(0xffffff);
  var scene = new THREE.Scene();
  scene.background = background;
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8899aa, 0.75));
  var sun = new THREE.DirectionalLight(0xffffff, 0.55);
  sun.position.set(1, 2, 3);
  scene.add(sun);
  var camera = new THREE.PerspectiveCamera(35, 1, 0.01, 100);
  var controls = new THREE.OrbitControls(camera, canvas);
  controls.addEventListener('change', render);

  var current = null;  // the scene shown: {index, meta, layers, root, ...}
  var frame = 0, playing = false, lastTick = 0;

  // ----- the side panel -----
  document.getElementById('title').textContent = site.title;
  document.getElementById('source').textContent = site.source;
  function gradient(element) {
    var stops = site.ramp.map(function (c, k) {
      return 'rgb(' + c.map(function (x) { return Math.round(255 * x); }).join(',') + ') ' + (10 * k) + '%';
    });
    element.style.background = 'linear-gradient(to right, ' + stops.join(', ') + ')';
  }
  gradient(document.getElementById('error-ramp'));
  gradient(document.getElementById('curve-ramp'));
  document.getElementById('error-top').textContent = site.error_scale_cm + ' cm and more';
  document.getElementById('curve-top').textContent = site.curve_scale_deg + ' deg and more';
  var list = document.getElementById('scenes');
  var links = [];
  var group = null;
  site.scenes.forEach(function (entry, index) {
    if (entry.group !== group) {
      group = entry.group;
      var heading = document.createElement('div');
      heading.className = 'group';
      heading.textContent = group;
      list.appendChild(heading);
    }
    var link = document.createElement('a');
    link.textContent = entry.name + (entry.frames > 1 ? ' (' + entry.frames + ' frames)' : '');
    link.addEventListener('click', function () { open(index); });
    list.appendChild(link);
    links.push(link);
  });
  function choice(name) { return document.querySelector('input[name="' + name + '"]:checked').value; }
  var checkedByUser = false;
  document.querySelectorAll('input[name="truth"], input[name="color"], #side input[type="checkbox"]')
      .forEach(function (input) { input.addEventListener('change', update); });
  document.querySelectorAll('input[name="color"]')
      .forEach(function (input) { input.addEventListener('change', function () { checkedByUser = true; }); });

  // ----- loading a scene -----
  var pending = {};
  function open(index) {
    if (index < 0 || index >= site.scenes.length) { fail('no scene ' + index); return; }
    links.forEach(function (link, k) { link.className = k === index ? 'current' : ''; });
    pending[index] = true;
    var script = document.createElement('script');
    script.src = site.scenes[index].script;
    script.onerror = function () { fail('could not load ' + site.scenes[index].script); };
    document.body.appendChild(script);
  }

  function decode(text) {
    var binary = atob(text);
    var bytes = new Uint8Array(binary.length);
    for (var i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
    return bytes.buffer;
  }

  window.pixelclothView = {
    sceneLoaded: function (index, glb, meta) {
      if (!pending[index]) return;
      delete pending[index];
      new THREE.GLTFLoader().parse(decode(glb), '', function (gltf) { show(index, gltf, meta); },
                                   function (error) { fail('scene ' + index + ': ' + (error.message || error)); });
    }
  };

  // A mesh of the GLB as a layer whose positions this page sets per frame.
  function layer(mesh, color, wire) {
    var source = mesh.geometry;
    var geometry = new THREE.BufferGeometry();
    var base = source.attributes.position.array;
    geometry.setIndex(source.index);
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(base), 3));
    var colors = { plain: source.attributes.color, error: source.attributes._error, patch: source.attributes._patch };
    if (!colors.plain) {  // the body: one colour
      var grey = new Float32Array(base.length);
      for (var i = 0; i < grey.length; i += 3) grey.set([0.78, 0.74, 0.70], i);
      colors.plain = new THREE.BufferAttribute(grey, 3);
    }
    geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(colors.plain.array), 3));
    geometry.computeVertexNormals();
    var material = wire
        ? new THREE.MeshBasicMaterial({ color: color, wireframe: true, transparent: true, opacity: 0.35 })
        : new THREE.MeshLambertMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide,
                                          polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
    var object = new THREE.Mesh(geometry, material);
    var deltas = (source.morphAttributes.position || []).map(function (a) { return a.array; });
    return { object: object, base: base, deltas: deltas, colors: colors, vertices: base.length / 3 };
  }

  function setFrame(item, f) {
    var position = item.object.geometry.attributes.position;
    var target = position.array, base = item.base;
    var delta = f > 0 && f <= item.deltas.length ? item.deltas[f - 1] : null;
    for (var i = 0; i < target.length; ++i) target[i] = delta ? base[i] + delta[i] : base[i];
    position.needsUpdate = true;
    item.object.geometry.computeVertexNormals();
    item.object.geometry.computeBoundingSphere();
  }

  function show(index, gltf, meta) {
    if (current) scene.remove(current.root);
    var meshes = {};
    gltf.scene.traverse(function (object) { if (object.isMesh) meshes[object.name] = object; });
    var root = new THREE.Group();
    var shown = { index: index, meta: meta, root: root, garments: [], body: null };
    if (meta.body) {
      if (!meshes[meta.body.node]) { fail('scene ' + index + ': no mesh ' + meta.body.node); return; }
      shown.body = layer(meshes[meta.body.node]);
      root.add(shown.body.object);
    }
    meta.garments.forEach(function (entry) {
      var mesh = meshes[entry.node];
      if (!mesh) { fail('scene ' + index + ': no mesh ' + entry.node); return; }
      var item = layer(mesh);
      item.entry = entry;
      if (entry.truth) item.wire = layer(mesh, 0x2a8a2a, true);
      shown.garments.push(item);
      root.add(item.object);
      if (item.wire) root.add(item.wire.object);
    });
    shown.truth = shown.garments.filter(function (g) { return g.entry.truth; })[0] || null;
    shown.bodyBeside = shown.body ? new THREE.Mesh(shown.body.object.geometry, shown.body.object.material) : null;
    if (shown.bodyBeside) root.add(shown.bodyBeside);
    // Cage curves over the first garment that is not ground truth (else the first), markers as points.
    var segments = [], colors = [];
    meta.curves.forEach(function (curve) {
      for (var k = 0; k < curve.segments.length; ++k) {
        segments.push(curve.segments[k]);
        colors.push(curve.color[0], curve.color[1], curve.color[2]);
      }
    });
    var curveGeometry = new THREE.BufferGeometry();
    curveGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * segments.length), 3));
    curveGeometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(colors), 3));
    shown.curves = new THREE.LineSegments(curveGeometry,
                                          new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors }));
    shown.curveVertices = segments;
    root.add(shown.curves);
    shown.markers = new THREE.Points(new THREE.BufferGeometry(),
                                     new THREE.PointsMaterial({ color: 0xd01010, size: 7, sizeAttenuation: false }));
    root.add(shown.markers);
    scene.add(root);
    current = shown;

    // The garment list: every garment but ground truth can be the one shown.
    var choices = document.getElementById('garments');
    choices.innerHTML = '';
    var first = true;
    shown.garments.forEach(function (item, k) {
      if (item.entry.truth && shown.garments.length > 1) return;
      var label = document.createElement('label');
      var input = document.createElement('input');
      input.type = 'radio';
      input.name = 'garment';
      input.value = k;
      input.checked = first;
      first = false;
      input.addEventListener('change', update);
      label.appendChild(input);
      var text = item.entry.name;
      if (item.entry.error) text += ' (' + item.entry.mean_error_cm.toFixed(3) + ' cm mean error)';
      label.appendChild(document.createTextNode(' ' + text));
      choices.appendChild(label);
    });
    // Colour choices the scene has: errors need ground truth, patches the garment's pattern.
    var hasError = meta.garments.some(function (g) { return g.error; });
    var colorInput = function (value) { return document.querySelector('input[name="color"][value="' + value + '"]'); };
    colorInput('error').disabled = !hasError;
    colorInput('patch').disabled = meta.patches === 0;
    if (colorInput(choice('color')).disabled || (hasError && !checkedByUser)) {
      colorInput(hasError ? 'error' : 'plain').checked = true;
    }
    document.getElementById('error-legend').style.opacity = hasError ? 1 : 0.35;
    document.getElementById('truth-choice').style.display = shown.truth && shown.garments.length > 1 ? '' : 'none';
    document.getElementById('curve-measure').textContent = meta.curve_measure;
    document.getElementById('info').textContent = describe(meta);
    var timeline = document.getElementById('timeline');
    var slider = document.getElementById('frame');
    timeline.style.display = meta.frames > 1 ? 'flex' : 'none';
    slider.max = meta.frames - 1;
    frame = 0;
    slider.value = 0;
    frameTo(0);
    frameCamera();
    update();
    status.ready = true;
    if (checkAll) record(index);
    report();
  }

  function describe(meta) {
    var lines = [];
    meta.garments.forEach(function (g) {
      lines.push(g.name + ': ' + g.vertices + ' vertices' + (g.error ? ', ' + g.mean_error_cm.toFixed(3) + ' cm' : ''));
    });
    if (meta.body) lines.push('body: ' + meta.body.vertices + ' vertices');
    if (meta.frames > 1) lines.push(meta.frames + ' frames at ' + meta.fps.toFixed(1) + ' fps');
    Object.keys(meta.info).forEach(function (key) {
      var value = meta.info[key];
      if (value === null || value === '') return;
      if (typeof value === 'number') value = Number.isInteger(value) ? value : value.toFixed(4);
      else if (typeof value === 'object') value = JSON.stringify(value);
      lines.push(key + ': ' + value);
    });
    return lines.join('\n');
  }

  function selectedGarment() {
    var input = document.querySelector('input[name="garment"]:checked');
    return current.garments[input ? Number(input.value) : 0];
  }

  // ----- what is drawn -----
  function frameTo(f) {
    frame = f;
    if (current.body) setFrame(current.body, f);
    current.garments.forEach(function (item) {
      setFrame(item, f);
      if (item.wire) setFrame(item.wire, f);
    });
    var garment = selectedGarment();
    var source = garment.object.geometry.attributes.position.array;
    var line = current.curves.geometry.attributes.position;
    current.curveVertices.forEach(function (v, k) {
      for (var c = 0; c < 3; ++c) line.array[3 * k + c] = source[3 * v + c];
    });
    line.needsUpdate = true;
    current.curves.geometry.computeBoundingSphere();
    var markers = current.meta.markers;
    var points = [];
    if (markers.length > 0) {
      markers[Math.min(f, markers.length - 1)].forEach(function (p) { if (p) points.push(p[0], p[1], p[2]); });
    }
    current.markers.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(points), 3));
    current.markers.geometry.computeBoundingSphere();
    current.visibleMarkers = points.length / 3;
    document.getElementById('frame-label').textContent = 'frame ' + (f + 1) + ' of ' + current.meta.frames;
  }

  function update() {
    if (!current) return;
    var garment = selectedGarment();
    var truthMode = choice('truth');
    var colorMode = choice('color');
    var box = new THREE.Box3().setFromObject(garment.object);
    var shift = 1.3 * (box.max.x - box.min.x) + 0.2;
    current.garments.forEach(function (item) {
      var isTruth = item === current.truth && item !== garment;
      item.object.visible = item === garment || (isTruth && truthMode === 'beside');
      item.object.position.x = isTruth && truthMode === 'beside' ? shift : 0;
      if (item.wire) item.wire.object.visible = isTruth && truthMode === 'overlay';
      var colors = item.colors[colorMode] || item.colors.plain;
      var attribute = item.object.geometry.attributes.color;
      attribute.array.set(colors.array);
      attribute.needsUpdate = true;
    });
    var body = document.getElementById('show-body').checked;
    if (current.body) current.body.object.visible = body;
    if (current.bodyBeside) {
      current.bodyBeside.visible = body && !!current.truth && current.truth !== garment && truthMode === 'beside';
      current.bodyBeside.position.x = shift;
    }
    current.curves.visible = document.getElementById('show-curves').checked;
    current.markers.visible = document.getElementById('show-markers').checked;
    frameTo(frame);
    render();
  }

  function frameCamera() {
    // The body and the garments (an empty set of markers has no bounds).
    var box = new THREE.Box3();
    if (current.body) box.expandByObject(current.body.object);
    current.garments.forEach(function (item) { box.expandByObject(item.object); });
    var center = box.getCenter(new THREE.Vector3());
    var size = box.getSize(new THREE.Vector3()).length();
    controls.target.copy(center);
    camera.position.set(center.x + 0.35 * size, center.y + 0.15 * size, center.z + 1.45 * size);
    camera.near = size / 100;
    camera.far = size * 20;
    camera.updateProjectionMatrix();
    controls.update();
  }

  function resize() {
    var width = canvas.clientWidth, height = canvas.clientHeight;
    renderer.setSize(width, height, false);
    camera.aspect = width / Math.max(1, height);
    camera.updateProjectionMatrix();
  }

  function render() {
    resize();
    renderer.render(scene, camera);
  }

  // Pixels of the canvas that are not background: a blank canvas has none.
  function drawnPixels() {
    var gl = renderer.getContext();
    var width = gl.drawingBufferWidth, height = gl.drawingBufferHeight;
    var pixels = new Uint8Array(4 * width * height);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    var drawn = 0;
    for (var i = 0; i < pixels.length; i += 4)
      if (Math.abs(pixels[i] - 255) + Math.abs(pixels[i + 1] - 255) + Math.abs(pixels[i + 2] - 255) > 24) ++drawn;
    return { drawn: drawn, of: width * height };
  }

  function record(index) {
    var meta = current.meta;
    var entry = { index: index, name: meta.name, frames: meta.frames, meshes: {}, curves: meta.curves.length,
                  curve_segments: current.curveVertices.length / 2, markers: current.visibleMarkers };
    if (current.body) entry.meshes.body = current.body.vertices;
    current.garments.forEach(function (item) { entry.meshes[item.entry.name] = item.vertices; });
    render();
    var first = drawnPixels();
    entry.drawn_pixels = first.drawn;
    entry.canvas_pixels = first.of;
    if (meta.frames > 1) {
      // The last frame must differ from the first: the morph targets are applied.
      var before = selectedGarment().object.geometry.attributes.position.array.slice();
      frameTo(meta.frames - 1);
      render();
      var after = selectedGarment().object.geometry.attributes.position.array;
      var moved = 0;
      for (var i = 0; i < after.length; ++i) moved = Math.max(moved, Math.abs(after[i] - before[i]));
      entry.last_frame_moved_m = moved;
      entry.last_frame_drawn_pixels = drawnPixels().drawn;
      frameTo(0);
    }
    status.scenes.push(entry);
    if (index + 1 < site.scenes.length) open(index + 1);
    else status.done = true;
  }

  // ----- time -----
  var slider = document.getElementById('frame');
  slider.addEventListener('input', function () { frameTo(Number(slider.value)); render(); });
  document.getElementById('play').addEventListener('click', function () {
    playing = !playing;
    this.textContent = playing ? 'pause' : 'play';
    lastTick = performance.now();
    if (playing) requestAnimationFrame(tick);
  });
  function tick(now) {
    if (!playing || !current) return;
    var step = Math.floor((now - lastTick) * current.meta.fps / 1000);
    if (step > 0) {
      lastTick += step * 1000 / current.meta.fps;
      frameTo((frame + step) % current.meta.frames);
      slider.value = frame;
      render();
    }
    requestAnimationFrame(tick);
  }
  window.addEventListener('resize', render);

  status.scene_count = site.scenes.length;
  report();
  if (site.scenes.length === 0) { fail('no scenes'); return; }
  open(checkAll ? 0 : Math.min(Math.max(Number(params.get('scene') || 0), 0), site.scenes.length - 1));
})();
