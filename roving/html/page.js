// The heat-map page's viewer: the embedded surfaces drawn by three.js, orbit / zoom / pan,
// the colour bar, picking, the toggle between directions, and where both models have colour the
// choice of what the surface shows (d, delta E, REF's or TEST's colour). Data come from the JSON block
// #roving-data, written by roving/html/html_page.cpp (arrays as base64 little-endian binary).
'use strict';
(function () {
  const data = JSON.parse(document.getElementById('roving-data').textContent);
  const RESOLUTION = ['no hit', 'a view (viewpoint sampling)', 'its own camera (surface roving)'];

  function decode(base64, Type) {
    if (!base64) return null;
    const text = atob(base64);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    return new Type(bytes.buffer);
  }
  function number(x) { return Number(x.toPrecision(4)).toString(); }

  const canvas = document.getElementById('view');
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
  } catch (error) {
    document.getElementById('pick').textContent = 'This page needs WebGL, which this browser does not offer: ' + error.message;
    throw error;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xffffff);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(30, 1, 1, 10);
  // A headlight along the view: a face turned to the viewer shows its colour exactly (0.35 + 0.65).
  const light = new THREE.DirectionalLight(0xffffff, 0.65);
  light.position.set(0, 0, 1);
  camera.add(light, light.target);
  scene.add(new THREE.AmbientLight(0xffffff, 0.35));
  scene.add(camera);
  const controls = new THREE.OrbitControls(camera, canvas);
  controls.screenSpacePanning = true;
  const views = data.views.map(function (view) { return { data: view, object: null }; });
  let current = null;
  // What the surface shows: d, or where both models have colour, delta E or either model's colour;
  // first the layer the command asked for (--heatmap-of).
  let shown = data.shown_first || 'd';

  function build(view) {
    const v = view.data;
    const source = v.geometry_of >= 0 ? data.views[v.geometry_of] : v;  // a surface shared with another view
    const positions = decode(source.positions, Float32Array);
    const triangles = decode(source.triangles, Uint32Array);
    view.layers = { d: decode(v.colours, Uint8Array) };  // per element, three bytes each
    if (v.colours_of) {
      view.layers.delta_e = decode(v.colours_of.delta_e_colours, Uint8Array);
      view.layers.reference = decode(v.colours_of.reference, Uint8Array);
      view.layers.test = decode(v.colours_of.test, Uint8Array);
      view.deltaE = decode(v.colours_of.delta_e, Float32Array);
    }
    const geometry = new THREE.BufferGeometry();
    if (v.element === 'faces') {  // flat colour per triangle: three vertices of its own
      const count = triangles.length;
      const p = new Float32Array(count * 3);
      for (let i = 0; i < count; ++i) {
        const vertex = triangles[i];
        for (let k = 0; k < 3; ++k) p[3 * i + k] = positions[3 * vertex + k];
      }
      geometry.setAttribute('position', new THREE.BufferAttribute(p, 3));
      geometry.setAttribute('color', new THREE.BufferAttribute(new Uint8Array(count * 3), 3, true));
    } else {
      geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
      geometry.setAttribute('color', new THREE.BufferAttribute(new Uint8Array(positions.length), 3, true));
      if (triangles) geometry.setIndex(new THREE.BufferAttribute(triangles, 1));
    }
    view.triangles = triangles;
    geometry.computeBoundingSphere();
    if (!triangles) {
      const size = v.point_size > 0 ? v.point_size : 1.5 * v.diagonal / Math.sqrt(positions.length / 3);
      view.pointSize = size;
      // three.js scales a point by half the canvas height over its depth, leaving out the field of
      // view: divide by tan(fov / 2) for disks of `size` model units.
      const drawn = size / Math.tan(camera.fov / 2 * Math.PI / 180);
      view.object = new THREE.Points(geometry, new THREE.PointsMaterial({ size: drawn, vertexColors: THREE.VertexColors }));
    } else {
      geometry.computeVertexNormals();
      view.object = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide }));
    }
    paint(view);
    view.values = decode(v.values, Float32Array);
    view.samples = decode(v.samples, Int32Array);
    view.resolution = decode(v.resolution, Uint8Array);
    view.elements = view.values.length;
  }

  // The element colours of the layer shown into the geometry (a face's onto its three vertices).
  function paint(view) {
    const colours = view.layers[shown] || view.layers.d;
    const attribute = view.object.geometry.attributes.color;
    if (view.data.element === 'faces') {
      for (let i = 0; i < view.triangles.length; ++i) {
        const face = (i / 3) | 0;
        for (let k = 0; k < 3; ++k) attribute.array[3 * i + k] = colours[3 * face + k];
      }
    } else {
      attribute.array.set(colours);
    }
    attribute.needsUpdate = true;
  }

  // The colour bar, its labels and the swatches for what is shown.
  function legend(v) {
    const bar = document.getElementById('colourbar'), units = document.getElementById('bar-units');
    const labels = document.getElementById('bar-labels');
    const own = shown === 'reference' || shown === 'test';
    bar.hidden = labels.hidden = own;
    document.querySelectorAll('#swatches .for-d').forEach(function (e) { e.hidden = shown !== 'd'; });
    document.querySelectorAll('#shown button').forEach(function (b) { b.classList.toggle('on', b.dataset.show === shown); });
    if (shown === 'd') {
      bar.style.background = bar.dataset.d;
      document.getElementById('bar-low').textContent = '\u2212' + number(v.range);
      document.getElementById('bar-middle').textContent = '0';
      document.getElementById('bar-high').textContent = '+' + number(v.range);
      units.textContent = 'd in model units; \u00b1' + number(v.range) + ' is ' + number(100 * v.range / v.diagonal) +
          '% of the diagonal (' + number(v.diagonal) + ')';
    } else if (shown === 'delta_e') {
      const top = v.colours_of.delta_e_range;
      bar.style.background = bar.dataset.deltaE;
      document.getElementById('bar-low').textContent = '0';
      document.getElementById('bar-middle').textContent = number(top / 2);
      document.getElementById('bar-high').textContent = number(top);
      units.textContent = 'CIEDE2000 delta E between REF\u2019s and TEST\u2019s colours at each sample; the top, ' +
          number(top) + ', is its 99th percentile';
    } else {
      units.textContent = shown === 'reference' ? 'REF\u2019s own colour at each sample'
                                                : 'TEST\u2019s colour where each sample\u2019s line meets it';
    }
  }

  function frame(view) {  // from +z, as the PNG's front view, the whole surface in sight
    const sphere = view.object.geometry.boundingSphere;
    const distance = sphere.radius / Math.sin(camera.fov / 2 * Math.PI / 180) * 1.05;
    camera.near = distance / 100;
    camera.far = distance * 100;
    camera.position.copy(sphere.center).add(new THREE.Vector3(0, 0, distance));
    camera.up.set(0, 1, 0);
    controls.target.copy(sphere.center);
    camera.updateProjectionMatrix();
    controls.update();
  }

  function show(index) {
    const view = views[index];
    if (!view.object) build(view);
    if (current) scene.remove(current.object);
    scene.add(view.object);
    // Points are drawn unlit: near-white ones (d near 0) need a background they stand out from.
    renderer.setClearColor(view.data.element === 'points' ? 0xd0d0d0 : 0xffffff);
    current = view;
    frame(view);
    const v = view.data;
    if (!v.colours_of) shown = 'd';
    document.getElementById('shown').hidden = !v.colours_of;
    paint(view);
    legend(v);
    document.getElementById('decimated').textContent = v.decimated;
    document.querySelectorAll('.direction').forEach(function (section, i) { section.hidden = i !== index; });
    document.querySelectorAll('#directions button').forEach(function (button, i) { button.classList.toggle('on', i === index); });
    document.getElementById('pick').textContent = v.pick_hint;
    render();
  }

  function render() {
    const width = canvas.clientWidth, height = canvas.clientHeight;
    if (canvas.width !== Math.floor(width * renderer.getPixelRatio()) || canvas.height !== Math.floor(height * renderer.getPixelRatio())) {
      renderer.setSize(width, height, false);
      camera.aspect = width / Math.max(height, 1);
      camera.updateProjectionMatrix();
    }
    renderer.render(scene, camera);
  }

  // Picking: what the element under the pointer shows, and the sample behind it.
  const raycaster = new THREE.Raycaster();
  function pick(event) {
    const box = canvas.getBoundingClientRect();
    const pointer = new THREE.Vector2((event.clientX - box.left) / box.width * 2 - 1, -(event.clientY - box.top) / box.height * 2 + 1);
    raycaster.setFromCamera(pointer, camera);
    if (current.pointSize) raycaster.params.Points.threshold = current.pointSize / 2;
    const hit = raycaster.intersectObject(current.object)[0];
    const out = document.getElementById('pick');
    if (!hit) { out.textContent = current.data.pick_hint; return; }
    const v = current.data;
    let element;
    if (v.element === 'faces') element = hit.faceIndex;
    else if (v.element === 'points') element = hit.index;
    else {  // the triangle's vertex nearest the pointer's hit
      const p = current.object.geometry.attributes.position, f = hit.face;
      let best = Infinity;
      [f.a, f.b, f.c].forEach(function (i) {
        const d = hit.point.distanceToSquared(new THREE.Vector3(p.getX(i), p.getY(i), p.getZ(i)));
        if (d < best) { best = d; element = i; }
      });
    }
    const value = current.values[element], sample = current.samples ? current.samples[element] : element;
    const where = v.element === 'faces' ? 'triangle ' : v.element === 'vertices' ? 'vertex ' : 'point ';
    let text = where + element + ': ';
    if (sample === -1) text += 'no sample here (a zero-area face)';
    else if (sample === -2) text += isNaN(value) ? 'merged for display; mostly no hit' : 'merged for display; mean d = ' + number(value);
    else {
      text += 'sample ' + sample + ', ';
      text += isNaN(value) ? 'no hit within h = ' + number(v.max_error) : 'd = ' + number(value) + ' (' + number(100 * value / v.diagonal) + '% of the diagonal)';
      text += current.resolution ? ', resolved by ' + RESOLUTION[current.resolution[sample]] : ', by ' + v.method + ' (exact)';
    }
    if (current.deltaE && sample !== -1) {
      const rgb = function (layer) {
        const c = current.layers[layer];
        return '(' + c[3 * element] + ', ' + c[3 * element + 1] + ', ' + c[3 * element + 2] + ')';
      };
      const e = current.deltaE[element];
      text += isNaN(e) ? '; REF\u2019s colour ' + rgb('reference') + ', no TEST colour'
                       : '; delta E = ' + number(e) + ', REF\u2019s colour ' + rgb('reference') + ', TEST\u2019s ' + rgb('test');
    }
    out.textContent = text;
  }
  let pending = null;
  canvas.addEventListener('pointermove', function (event) {
    if (current.elements > 300000 || event.buttons) return;  // large surfaces: on click only
    if (!pending) requestAnimationFrame(function () { pick(pending); pending = null; });
    pending = event;
  });
  canvas.addEventListener('click', pick);
  controls.addEventListener('change', render);
  window.addEventListener('resize', render);
  document.querySelectorAll('#directions button').forEach(function (button, i) {
    button.addEventListener('click', function () { show(i); });
  });
  document.querySelectorAll('#shown button').forEach(function (button) {
    button.addEventListener('click', function () {
      shown = button.dataset.show;
      paint(current);
      legend(current.data);
      render();
    });
  });
  show(0);
  document.body.dataset.ready = 'true';
})();
