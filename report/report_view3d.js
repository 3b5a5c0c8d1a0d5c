// report.html's 3D view (report/report_view3d.h): draws the grid shell of the JSON in
// #view3d-data with three.js (r111, inlined before this script), faces coloured by the
// metric picked, members as lines, the reference faint; OrbitControls rotate, zoom and pan.
// Once drawn it measures itself into the section's data-check (scripts/check_report.sh).
// Compiled into pqlayout (cmake/EmbedFiles.cmake); plain ES2017, no modules.
(function () {
  'use strict';
  const section = document.getElementById('view3d');
  const part = name => section.querySelector('.v3d-' + name);
  const kAzimuth = 240, kElevation = 35;  // first view: from the south-west, as shell_3d.svg
  const kCheckTurn = 30;                  // degrees the self-check turns the camera by

  // The view replaced by one line (no WebGL, unreadable data): figures stay as they are.
  function giveUp(check, message) {
    section.dataset.check = check;
    for (const name of ['controls', 'canvas', 'key']) part(name).style.display = 'none';
    part('note').textContent = message;
  }

  function hasWebgl() {
    try {
      const canvas = document.createElement('canvas');
      return !!(window.WebGLRenderingContext &&
                (canvas.getContext('webgl') || canvas.getContext('experimental-webgl')));
    } catch (e) {
      return false;
    }
  }

  // Faces [n, i_1..i_n, ...] as a triangle fan each: corner vertex indices, face per triangle.
  function triangulate(faces) {
    const corners = [], faceOf = [];
    let f = 0;
    for (let at = 0; at < faces.length; at += faces[at] + 1, ++f) {
      const n = faces[at];
      if (!(n >= 1)) break;
      for (let k = 1; k + 1 < n; ++k) {
        corners.push(faces[at + 1], faces[at + 1 + k], faces[at + 2 + k]);
        faceOf.push(f);
      }
    }
    return {corners, faceOf, faces: f};
  }

  // Every edge of the faces once, as pairs of vertex indices.
  function members(faces) {
    const seen = new Set(), pairs = [];
    for (let at = 0; at < faces.length && faces[at] >= 1; at += faces[at] + 1) {
      const n = faces[at];
      for (let k = 0; k < n; ++k) {
        const a = faces[at + 1 + k], b = faces[at + 1 + (k + 1) % n];
        const key = Math.min(a, b) + ',' + Math.max(a, b);
        if (!seen.has(key)) {
          seen.add(key);
          pairs.push(a, b);
        }
      }
    }
    return pairs;
  }

  // Float32Array of the coordinates of `indices` (3 per index) out of xyz.
  function gather(xyz, indices) {
    const out = new Float32Array(3 * indices.length);
    indices.forEach((v, i) => out.set([xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]], 3 * i));
    return out;
  }

  function geometry(positions) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    return g;
  }

  // Position 0..1 of a value on a metric's scale (log: below lo is 0, as in the figures).
  function scaleT(metric, value) {
    let t;
    if (metric.log) t = value > metric.lo ? Math.log(value / metric.lo) / Math.log(metric.hi / metric.lo) : 0;
    else t = metric.hi > metric.lo ? (value - metric.lo) / (metric.hi - metric.lo) : 0.5;
    return Math.min(1, Math.max(0, isFinite(t) ? t : 0));
  }

  // The metric's colour at t, interpolated between its stops (sampled from the C++ maps).
  function colourAt(metric, t) {
    if (!metric.rgb) metric.rgb = metric.stops.map(hex => new THREE.Color(hex));
    const x = t * (metric.rgb.length - 1), i = Math.min(Math.floor(x), metric.rgb.length - 2);
    return metric.rgb[i].clone().lerp(metric.rgb[i + 1], x - i);
  }

  function format(value, unit) {
    return String(+Number(value).toPrecision(3)) + (unit ? ' ' + unit : '');
  }

  // The colour bar: gradient, ends, the marked value, the metric's range over the faces.
  function showKey(metric) {
    part('bar').style.background = 'linear-gradient(to right,' + metric.stops.join(',') + ')';
    part('lo').textContent = format(metric.lo, metric.unit);
    part('hi').textContent = format(metric.hi, metric.unit);
    const mark = part('mark');
    mark.style.display = metric.mark ? '' : 'none';
    if (metric.mark) mark.style.left = (100 * scaleT(metric, metric.mark)) + '%';
    part('label').textContent = metric.name + (metric.mark ? ' (| ' + metric.mark_label + ' ' +
        format(metric.mark, metric.unit) + ')' : '') + '; over the faces: min ' +
        format(metric.min, metric.unit) + ', max ' + format(metric.max, metric.unit);
  }

  function buildShell(data, view) {
    const {corners, faceOf, faces} = triangulate(data.faces);
    const shell = geometry(gather(data.vertices, corners));
    shell.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * corners.length), 3));
    shell.computeVertexNormals();
    shell.computeBoundingSphere();
    view.shell = shell;
    view.faceOf = faceOf;
    view.faces = faces;
    view.scene.add(new THREE.Mesh(shell, new THREE.MeshLambertMaterial({
      vertexColors: THREE.VertexColors, side: THREE.DoubleSide,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1})));
    view.members = new THREE.LineSegments(geometry(gather(data.vertices, members(data.faces))),
        new THREE.LineBasicMaterial({color: 0x282828, transparent: true, opacity: 0.7}));
    view.scene.add(view.members);
  }

  // The reference: its triangles faint in the backdrop (drawn first, so the shell, on or
  // near it, always covers it and it shows only around and through the shell), its boundary
  // as lines in the scene.
  function buildReference(surface, view) {
    view.reference = [new THREE.Group(), new THREE.Group()];
    if (surface && surface.triangles && surface.triangles.length > 0) {
      view.reference[0].add(new THREE.Mesh(geometry(gather(surface.vertices, surface.triangles)),
          new THREE.MeshBasicMaterial({color: 0x8a9099, transparent: true, opacity: 0.2,
                                       side: THREE.DoubleSide, depthWrite: false})));
    }
    for (const loop of (surface && surface.boundary) || [])
      view.reference[1].add(new THREE.LineLoop(geometry(Float32Array.from(loop)),
          new THREE.LineBasicMaterial({color: 0x8a8a8a})));
    view.backdrop.add(view.reference[0]);
    view.scene.add(view.reference[1]);
  }

  function colourBy(metric, view) {
    const colour = view.shell.getAttribute('color');
    view.faceOf.forEach((f, triangle) => {
      const c = colourAt(metric, scaleT(metric, metric.values[f]));
      for (let k = 0; k < 3; ++k) colour.setXYZ(3 * triangle + k, c.r, c.g, c.b);
    });
    colour.needsUpdate = true;
    // Members dark on light faces, light on dark ones (viridis is mostly dark).
    let luminance = 0;
    for (let i = 0; i < colour.count; ++i) luminance += 0.3 * colour.getX(i) + 0.6 * colour.getY(i) + 0.1 * colour.getZ(i);
    const dark = luminance < 0.4 * colour.count;
    view.members.material.color.set(dark ? 0xf4f4f4 : 0x282828);
    view.members.material.opacity = dark ? 0.45 : 0.7;
    showKey(metric);
    view.render();
  }

  // The shell's extent on the screen, in normalised device coordinates.
  function screenBox(view) {
    const points = view.shell.getAttribute('position'), p = new THREE.Vector3(), box = new THREE.Box2();
    view.camera.updateMatrixWorld();
    for (let i = 0; i < points.count; ++i) {
      p.fromBufferAttribute(points, i).project(view.camera);
      box.expandByPoint(new THREE.Vector2(p.x, p.y));
    }
    return box;
  }

  // Camera from kAzimuth/kElevation, z up, the shell centred and filling 90 % of the
  // canvas's width or height (the extent on screen goes nearly as 1/distance: 3 passes).
  function resetCamera(view) {
    const sphere = view.shell.boundingSphere, camera = view.camera, target = view.controls.target;
    const az = kAzimuth * Math.PI / 180, el = kElevation * Math.PI / 180;
    const direction = new THREE.Vector3(Math.cos(el) * Math.cos(az), Math.cos(el) * Math.sin(az), Math.sin(el));
    let distance = (sphere.radius > 0 ? sphere.radius : 1) / Math.sin(camera.fov * Math.PI / 360);
    target.copy(sphere.center);
    for (let pass = 0; pass < 3; ++pass) {
      camera.position.copy(direction).multiplyScalar(distance).add(target);
      camera.lookAt(target);
      const box = screenBox(view), centre = box.getCenter(new THREE.Vector2()), size = box.getSize(new THREE.Vector2());
      if (box.isEmpty() || !isFinite(size.x + size.y) || Math.max(size.x, size.y) <= 0) break;
      const halfHeight = distance * Math.tan(camera.fov * Math.PI / 360);  // world units at the target
      target.add(new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0).multiplyScalar(centre.x * halfHeight * camera.aspect))
            .add(new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1).multiplyScalar(centre.y * halfHeight));
      distance *= Math.max(size.x, size.y) / 2 / 0.9;
    }
    camera.position.copy(direction).multiplyScalar(distance).add(target);
    camera.lookAt(target);
    camera.near = distance / 100;
    camera.far = distance * 10;
    camera.updateProjectionMatrix();
    view.controls.maxDistance = 4 * distance;
    view.controls.update();
  }

  function resize(view) {
    const holder = part('canvas'), width = Math.max(1, holder.clientWidth);
    const height = Math.max(1, holder.clientHeight);
    view.renderer.setSize(width, height);
    view.camera.aspect = width / height;
    view.camera.updateProjectionMatrix();
    view.render();
  }

  // The canvas scaled to 400 px wide on white: its RGBA bytes.
  function pixels(canvas) {
    const w = 400, h = Math.max(1, Math.round(w * canvas.height / canvas.width));
    const copy = document.createElement('canvas');
    copy.width = w;
    copy.height = h;
    const g = copy.getContext('2d');
    g.fillStyle = '#ffffff';
    g.fillRect(0, 0, w, h);
    g.drawImage(canvas, 0, 0, w, h);
    return g.getImageData(0, 0, w, h).data;
  }

  // Measures the view, turns the camera by kCheckTurn about the vertical, measures how much
  // of the picture changed, turns it back: section.dataset.check (report_view3d.h).
  function selfCheck(view) {
    view.render();
    const before = pixels(view.renderer.domElement);
    let ink = 0, changed = 0;
    const colours = new Set();
    for (let i = 0; i < before.length; i += 4) {
      if (before[i] < 245 || before[i + 1] < 245 || before[i + 2] < 245) ++ink;
      colours.add(((before[i] >> 4) << 8) | ((before[i + 1] >> 4) << 4) | (before[i + 2] >> 4));
    }
    const camera = view.camera, target = view.controls.target, saved = camera.position.clone();
    camera.position.sub(target).applyAxisAngle(camera.up, kCheckTurn * Math.PI / 180).add(target);
    camera.lookAt(target);
    view.render();
    const after = pixels(view.renderer.domElement);
    for (let i = 0; i < after.length; i += 4)
      if (Math.max(Math.abs(after[i] - before[i]), Math.abs(after[i + 1] - before[i + 1]),
                   Math.abs(after[i + 2] - before[i + 2])) > 24) ++changed;
    camera.position.copy(saved);
    camera.lookAt(target);
    view.render();
    const n = before.length / 4, box = view.renderer.domElement.getBoundingClientRect();
    section.dataset.check = 'w=' + Math.round(box.width) + ' h=' + Math.round(box.height) +
        ' faces=' + view.faces + ' ink=' + (ink / n).toFixed(3) + ' colours=' + colours.size +
        ' rotated=' + (changed / n).toFixed(3);
  }

  function wireControls(data, view) {
    const select = part('metric');
    data.metrics.forEach((metric, i) => select.add(new Option(metric.name, String(i))));
    select.addEventListener('change', () => colourBy(data.metrics[+select.value], view));
    const toggle = (name, objects) => part(name).addEventListener('change', event => {
      for (const object of objects) object.visible = event.target.checked;
      view.render();
    });
    toggle('members', [view.members]);
    toggle('reference', view.reference);
    part('reset').addEventListener('click', () => {
      resetCamera(view);
      view.render();
    });
  }

  function start(data) {
    const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setClearColor(0xffffff);
    renderer.autoClear = false;
    part('canvas').appendChild(renderer.domElement);
    const view = {renderer, scene: new THREE.Scene(), backdrop: new THREE.Scene(),
                  camera: new THREE.PerspectiveCamera(30, 2, 0.1, 1000)};
    view.render = () => {
      view.camera.updateMatrixWorld();  // a child of view.scene: not updated by the backdrop's pass
      renderer.clear();
      renderer.render(view.backdrop, view.camera);
      renderer.clearDepth();
      renderer.render(view.scene, view.camera);
    };
    view.camera.up.set(0, 0, 1);
    view.camera.add(new THREE.PointLight(0xffffff, 0.35));  // a headlight: lit where you look
    view.scene.add(view.camera, new THREE.AmbientLight(0xffffff, 0.7));
    buildShell(data, view);
    buildReference(data.surface, view);
    view.controls = new THREE.OrbitControls(view.camera, renderer.domElement);
    view.controls.addEventListener('change', view.render);
    resize(view);
    resetCamera(view);
    wireControls(data, view);
    if (window.ResizeObserver) new ResizeObserver(() => resize(view)).observe(part('canvas'));
    if (data.metrics.length > 0) colourBy(data.metrics[0], view);
    else part('key').style.display = 'none';
    return view;
  }

  if (!hasWebgl()) {
    giveUp('nowebgl', '3D view not shown: this browser provides no WebGL (the figures below show the same data).');
    return;
  }
  try {
    const view = start(JSON.parse(document.getElementById('view3d-data').textContent));
    const check = () => {
      try {
        selfCheck(view);
      } catch (e) {
        section.dataset.check = 'error ' + e;
      }
    };
    if (document.readyState === 'complete') check();
    else window.addEventListener('load', check);
  } catch (e) {
    giveUp('error ' + e, '3D view not shown: ' + e);
  }
})();
