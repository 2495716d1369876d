// The web viewer's state and input (web/viewer.html): a PRT bake relit by web/prt_transfer.js under an
// environment (an equirect .hdr/.exr projected to SH by web/sh.js, or a `prt light` JSON with its
// discs), prt's orbit camera driven by the mouse, the environment's rotation, the sun, exposure and
// tone map (probes/threejs/prt_tone_map.js), an optional probe volume (probes/threejs) in the same scene.
import { BackSide, FloatType, Matrix3, Mesh, MeshLambertMaterial, Scene, ShaderMaterial, SphereGeometry, SRGBColorSpace, Vector3,
         WebGLRenderer } from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';
import { RGBELoader } from 'three/addons/loaders/RGBELoader.js';
import { PrtRelighting, PrtTransferPlugin } from './prt_transfer.js';
import { orbitCamera, worldBounds } from './prt_camera.js';
import { fromLightFile, projectEquirect, rotationFromYawPitchRoll } from './sh.js';
import { setPrtToneMapping } from '../probes/threejs/prt_tone_map.js';
import { PrtProbeVolume } from '../probes/threejs/prt_probe_volume.js';

const numbers = (text, count, what) => {
  const v = String(text).split(',').map(Number);
  if (v.length !== count || v.some((x) => !Number.isFinite(x))) throw new Error(`${what} '${text}': expected ${count} numbers`);
  return v;
};

// The equirect background, as `prt render --background env` (without its discs): each pixel shows the
// map along its view direction turned by R_env^-1, in prt's equirect convention (docs/conventions.md).
function backgroundMesh(texture) {
  const material = new ShaderMaterial({
    uniforms: { map: { value: texture }, inverseRotation: { value: new Matrix3() } },
    vertexShader: `out vec3 direction;
      void main() { direction = (modelMatrix * vec4(position, 1.0)).xyz - cameraPosition;
                    gl_Position = projectionMatrix * viewMatrix * modelMatrix * vec4(position, 1.0); gl_Position.z = gl_Position.w; }`,
    fragmentShader: `uniform sampler2D map; uniform mat3 inverseRotation; in vec3 direction;
      void main() { vec3 d = normalize(inverseRotation * direction);
        vec2 uv = vec2(atan(d.z, d.x) * 0.15915494309189535 + 0.5, asin(clamp(d.y, -1.0, 1.0)) * 0.3183098861837907 + 0.5);
        gl_FragColor = vec4(texture2D(map, uv).rgb, 1.0);
        #include <tonemapping_fragment>
        #include <colorspace_fragment>
      }`,
    side: BackSide, depthWrite: false, depthTest: false,
  });
  const mesh = new Mesh(new SphereGeometry(1, 64, 32), material);
  mesh.renderOrder = -1;
  mesh.frustumCulled = false;
  mesh.onBeforeRender = (renderer, scene, camera) => { mesh.position.copy(camera.position); mesh.scale.setScalar(0.5 * (camera.near + camera.far)); };
  return mesh;
}

// The file name a URL or path ends with (the status line names files, not the folders they came from).
const fileName = (url) => decodeURIComponent(String(url).split(/[?#]/)[0].split('/').pop()) || String(url);

export class PrtViewer {
  constructor(container, params) {
    this.params = params;
    const size = params.get('size');
    this.fixedSize = size ? numbers(size.replace('x', ','), 2, 'size') : null;
    this.renderer = new WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(this.fixedSize ? 1 : window.devicePixelRatio);
    this.renderer.outputColorSpace = SRGBColorSpace;
    container.prepend(this.renderer.domElement);
    this.scene = new Scene();
    const camera = (params.get('camera') || 'auto').split(',');
    this.orbit = { azimuth: Number(camera[1] !== undefined ? camera[0] : 0), elevation: Number(camera[1] || 0),
                   distance: camera[2] === undefined || camera[0] === 'auto' || camera[2] === 'auto' ? 'auto' : Number(camera[2]) };
    this.lightAngles = params.get('rotate') ? numbers(params.get('rotate'), 3, 'rotate') : [0, 0, 0];
    this.sunEnabled = params.get('sun') !== 'off';
    this.shadingBands = Number(params.get('bands') || 0);  // prt view's --bands N (0: all)
    this.extraDisc = params.get('disc') ? numbers(params.get('disc'), 7, 'disc') : null;
    this.background = params.get('background') || 'env';
    this.setDisplay(Number(params.get('exposure') || 0), params.get('tonemap') || 'aces');
    this.onChange = () => {};
    this.installInput(this.renderer.domElement);
    addEventListener('resize', () => this.requestRender());
    this.requestRender();
  }

  describe() {
    const what = [];
    if (this.relighting) what.push(`${fileName(this.bakeName)}: ${this.relighting.meshes.length} meshes, ${this.relighting.models.map((m) => `${m.kind} ${m.bands} bands ${m.clusters}x${m.terms}`).join(', ')}`);
    if (this.lighting) what.push(`${fileName(this.lightingName)}: ${this.lighting.bands} bands, ${(this.lighting.discs || []).length} disc(s)`);
    return what.join('\n');
  }

  /// Loads a PRT_transfer .glb (replacing any previous bake) and frames it.
  async loadBake(url, name = url) {
    const loader = new GLTFLoader().register((parser) => new PrtTransferPlugin(parser));
    const gltf = await loader.loadAsync(url);
    if (this.gltf) this.scene.remove(this.gltf.scene);
    this.gltf = gltf;
    this.bakeName = name;
    this.relighting = new PrtRelighting(gltf);
    this.relighting.setBands(Math.min(this.shadingBands, this.relighting.bands));
    this.scene.add(gltf.scene);
    this.bounds = worldBounds(this.relighting.meshes);
    this.applyLighting();
    this.requestRender();
  }

  /// Loads lighting: .json (`prt light`), .hdr (RGBELoader) or .exr (EXRLoader), projected to SH here.
  async loadLighting(url, name = url) {
    this.lightingName = name;
    if (/\.json$/i.test(name)) {
      this.lightingSource = { file: fromLightFile(await (await fetch(url)).json()) };
    } else {
      const rgbe = /\.hdr$/i.test(name);
      const texture = await (rgbe ? new RGBELoader() : new EXRLoader()).setDataType(FloatType).loadAsync(url);
      this.lightingSource = { texture, rgbe };
      this.setBackground(texture);
    }
    this.applyLighting();
    this.requestRender();
  }

  /// Shows an equirect image (.hdr/.exr) as the background (with a .json lighting: the map it came from).
  async loadBackground(url, name = url) {
    const texture = await (/\.hdr$/i.test(name) ? new RGBELoader() : new EXRLoader()).setDataType(FloatType).loadAsync(url);
    this.setBackground(texture);
    this.requestRender();
  }

  setBackground(texture) {
    if (this.sky) this.scene.remove(this.sky);
    this.sky = this.background === 'env' ? backgroundMesh(texture) : null;
    if (this.sky) this.scene.add(this.sky);
  }

  /// Adds a sphere lit by a prt probe volume (probes/threejs) beside the bake.
  async loadProbes(url) {
    this.volume = await PrtProbeVolume.load(url);
    const radius = this.bounds ? 0.15 * this.bounds.min.distanceTo(this.bounds.max) : 0.5;
    const sphere = new Mesh(new SphereGeometry(radius, 64, 32), new MeshLambertMaterial({ color: 0xcccccc }));
    const at = this.bounds ? new Vector3(this.bounds.max.x + 1.5 * radius, this.bounds.min.y + radius, this.bounds.getCenter(new Vector3()).z) : new Vector3();
    sphere.position.copy(at);
    this.scene.add(sphere);
    this.volume.attach(sphere);
    this.probeSphere = sphere;
    this.requestRender();
  }

  // Projects an image to the bands the bake needs (and re-projects if a later bake needs more).
  applyLighting() {
    if (!this.lightingSource) return;
    const needed = this.relighting ? this.relighting.bands : 3;
    if (this.lightingSource.file) {
      this.lighting = this.lightingSource.file;
    } else if (!this.lighting || this.lighting.bands < needed || this.lighting.fromImage !== this.lightingSource.texture) {
      const coefficients = projectEquirect(this.lightingSource.texture, needed, { rgbe: this.lightingSource.rgbe });
      const discs = this.extraDisc ? [{ direction: this.extraDisc.slice(0, 3), irradiance: this.extraDisc.slice(3, 6),
                                        angular_radius_degrees: this.extraDisc[6] }] : [];
      this.lighting = { bands: needed, coefficients, discs, fromImage: this.lightingSource.texture };
    }
    if (this.relighting) this.relighting.setLighting(this.lighting);
  }

  setDisplay(exposure, toneMap) {
    setPrtToneMapping(this.renderer, exposure, toneMap);
    this.exposure = exposure;
    this.toneMap = toneMap;
    this.requestRender();
  }

  setSun(on) { this.sunEnabled = !!on; this.requestRender(); }

  setLightAngles(angles) { this.lightAngles = angles.slice(); this.requestRender(); }

  installInput(canvas) {
    let last = null;
    canvas.addEventListener('pointerdown', (e) => { last = { x: e.clientX, y: e.clientY }; canvas.setPointerCapture(e.pointerId); });
    canvas.addEventListener('pointerup', () => { last = null; });
    canvas.addEventListener('pointermove', (e) => {
      if (!last) return;
      const dx = e.clientX - last.x, dy = e.clientY - last.y;
      last = { x: e.clientX, y: e.clientY };
      if (e.shiftKey) {
        this.lightAngles = [this.lightAngles[0] + 0.4 * dx, Math.max(-89, Math.min(89, this.lightAngles[1] + 0.4 * dy)), this.lightAngles[2]];
      } else {
        this.orbit.azimuth -= 0.4 * dx;
        this.orbit.elevation = Math.max(-89, Math.min(89, this.orbit.elevation + 0.4 * dy));
      }
      this.requestRender();
      this.onChange();
    });
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      const current = this.view ? this.view.distance : 1;
      this.orbit.distance = current * Math.pow(1.1, Math.sign(e.deltaY));
      this.requestRender();
    }, { passive: false });
  }

  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => { this.pending = false; this.renderNow(); });
  }

  /// Renders one frame now (the tests call it directly).
  renderNow() {
    const [width, height] = this.fixedSize || [innerWidth, innerHeight];
    this.renderer.setSize(width, height);
    if (!this.relighting || !this.lighting) { this.renderer.render(this.scene, this.camera || orbitCamera(worldBounds([]), this.orbit, 1, 1).camera); return; }
    this.view = orbitCamera(this.bounds, this.orbit, width, height, this.camera);
    this.camera = this.view.camera;
    const R = rotationFromYawPitchRoll(...this.lightAngles);
    this.relighting.setRotation(R);
    this.relighting.setSunEnabled(this.sunEnabled);
    this.relighting.update(this.renderer);
    if (this.sky) this.sky.material.uniforms.inverseRotation.value.set(R[0], R[3], R[6], R[1], R[4], R[7], R[2], R[5], R[8]);
    this.renderer.render(this.scene, this.camera);
  }
}
