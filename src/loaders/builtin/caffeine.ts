/** The caffeine molecule (PubChem CID 2519) in ball-and-stick style, in the studio: the molecule importer's built-in example. */
import type { Scene } from '../../scene/types.ts';
import { CAFFEINE_MOL } from '../molecule/caffeine.ts';
import { parseMolfile } from '../molecule/molfile.ts';
import { moleculeScene } from '../molecule/to-scene.ts';

export function caffeineScene(): Scene {
  return moleculeScene(parseMolfile(CAFFEINE_MOL, 'caffeine.mol'), 'ball-and-stick', 'caffeine');
}
