// prt's orbit camera (src/camera/camera.h, docs/conventions.md "Rendering") as a three.js
// PerspectiveCamera, so that a page shows what `prt render --camera AZ,EL,DIST --size WxH` shows:
// c = centre of the world bounds of what was baked, r = half their diagonal; eye = c + DIST (sin AZ cos EL,
// sin EL, cos AZ cos EL) looking at c, up +Y; vertical field of view 40 degrees, aspect W / H,
// near = max(DIST - 1.01 r, 0.001 r), far = DIST + 1.01 r; DIST auto = 1.05 r / sin(min(fov_y, fov_x) / 2).
import { Box3, PerspectiveCamera, Vector3 } from 'three';

export const VERTICAL_FOV_DEGREES = 40;

/// World bounds of `objects` (their vertices, node transforms applied), as prt's mesh bounds.
export function worldBounds(objects) {
  const box = new Box3();
  for (const o of objects) { o.updateWorldMatrix(true, false); box.expandByObject(o, true); }
  return box;
}

/// Sets `camera` (or a new PerspectiveCamera) to prt's orbit view. azimuth, elevation in degrees
/// (|elevation| < 89.9), distance in scene units or 'auto'/<= 0 (frame the bounds); width, height >= 1.
export function orbitCamera(bounds, { azimuth = 0, elevation = 0, distance = 'auto' }, width, height, camera = new PerspectiveCamera()) {
  const centre = bounds.getCenter(new Vector3());
  const r = 0.5 * bounds.min.distanceTo(bounds.max);
  const fovY = VERTICAL_FOV_DEGREES * Math.PI / 180;
  const fovX = 2 * Math.atan(Math.tan(fovY / 2) * width / height);
  const dist = distance === 'auto' || !(distance > 0) ? 1.05 * r / Math.sin(Math.min(fovY, fovX) / 2) : distance;
  const az = azimuth * Math.PI / 180, el = elevation * Math.PI / 180;
  camera.fov = VERTICAL_FOV_DEGREES;
  camera.aspect = width / height;
  camera.near = Math.max(dist - 1.01 * r, 0.001 * r);
  camera.far = dist + 1.01 * r;
  camera.zoom = 1;
  camera.position.set(centre.x + dist * Math.sin(az) * Math.cos(el), centre.y + dist * Math.sin(el), centre.z + dist * Math.cos(az) * Math.cos(el));
  camera.up.set(0, 1, 0);
  camera.lookAt(centre);
  camera.updateProjectionMatrix();
  camera.updateMatrixWorld(true);
  return { camera, centre, radius: r, distance: dist };
}
