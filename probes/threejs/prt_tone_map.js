// prt's display transform for three.js (docs/conventions.md, "Images and tone mapping"): radiance x
// 2^exposure (negatives and NaN as 0), then ACES as Narkowicz's 2015 fit x (2.51x + 0.03) /
// (x (2.43x + 0.59) + 0.14) with no 0.6 pre-scale (three's own ACESFilmicToneMapping is a different
// curve, the Hill fit with exposure / 0.6) or 'clamp', clamped to [0, 1], then three's sRGB output
// encoding. 'none' is three's plain output (no exposure, no tone map), what the probe page showed before.
import { CustomToneMapping, LinearToneMapping, NoToneMapping, ShaderChunk } from 'three';

const NARKOWICZ_ACES = `vec3 CustomToneMapping( vec3 color ) {
	color *= toneMappingExposure;
	color = mix( vec3( 0.0 ), color, greaterThan( color, vec3( 0.0 ) ) );
	return saturate( ( color * ( 2.51 * color + 0.03 ) ) / ( color * ( 2.43 * color + 0.59 ) + 0.14 ) );
}`;

function installAces() {
  const chunk = ShaderChunk.tonemapping_pars_fragment;
  if (chunk.includes('2.51 * color')) return;
  const stub = 'vec3 CustomToneMapping( vec3 color ) { return color; }';
  if (!chunk.includes(stub)) throw new Error('prt_tone_map.js: this three.js has no CustomToneMapping stub to replace');
  ShaderChunk.tonemapping_pars_fragment = chunk.replace(stub, NARKOWICZ_ACES);
}

/// Sets renderer.toneMapping and toneMappingExposure for prt's display transform.
/// exposureStops: any finite number (stops, 2^exposure); toneMap: 'aces' | 'clamp' | 'none'.
/// Call before the first render of a material (three compiles the tone map into each program).
export function setPrtToneMapping(renderer, exposureStops, toneMap) {
  if (!Number.isFinite(exposureStops)) throw new RangeError(`exposure ${exposureStops} is not a finite number of stops`);
  if (toneMap === 'aces') {
    installAces();
    renderer.toneMapping = CustomToneMapping;
  } else if (toneMap === 'clamp') {
    renderer.toneMapping = LinearToneMapping;  // saturate(exposure * colour)
  } else if (toneMap === 'none') {
    renderer.toneMapping = NoToneMapping;
  } else {
    throw new RangeError(`tone map '${toneMap}' is not one of aces, clamp, none`);
  }
  renderer.toneMappingExposure = Math.pow(2, exposureStops);
}
