"""Noise, Musgrave, White Noise, Wave and Magic textures -> nodes/noise.inc (Cycles 3.4).

Enums are written as their Blender 3.4 enum_items indices:
- noise_dimensions / musgrave_dimensions 1D, 2D, 3D, 4D -> Dimensions 0..3;
- musgrave_type MULTIFRACTAL, RIDGED_MULTIFRACTAL, HYBRID_MULTIFRACTAL, FBM, HETERO_TERRAIN
  -> Type 0..4 (Blender's UI order, not Cycles' internal NodeMusgraveType order);
- wave_type BANDS, RINGS -> Type 0, 1; bands_direction X, Y, Z, DIAGONAL and
  rings_direction X, Y, Z, SPHERICAL -> BandsDirection / RingsDirection 0..3;
  wave_profile SIN, SAW, TRI -> Profile 0..2;
- Magic's turbulence_depth (an int) -> Depth.
Every unlinked Vector means Generated coordinates, as in Cycles.

Blender 4.x: 4.0 added Noise's Lacunarity (mapped: NoiseTexture has a Lacunarity socket,
2.0 = 3.4's fixed value) and Normalize (not mapped; 4.0 also changed the fBm normalisation,
which NoiseTexture does not follow); 4.1 folded Musgrave into Noise (noise_type) and removed
ShaderNodeTexMusgrave. Those settings are not listed here, so the exporter warns about them.
"""
from ..spec import NodeSpec

NODES = {
    'ShaderNodeTexNoise': NodeSpec(
        mgraph='NoiseTexture',
        inputs={'Vector': 'Vector', 'W': 'W', 'Scale': 'Scale', 'Detail': 'Detail',
                'Roughness': 'Roughness', 'Lacunarity': 'Lacunarity',
                'Distortion': 'Distortion'},
        outputs={'Fac': 'Fac', 'Color': 'Color'},
        props={'noise_dimensions': 'Dimensions'},
        implicit_vector='generated'),
    'ShaderNodeTexMusgrave': NodeSpec(
        mgraph='MusgraveTexture',
        inputs={'Vector': 'Vector', 'W': 'W', 'Scale': 'Scale', 'Detail': 'Detail',
                'Dimension': 'Dimension', 'Lacunarity': 'Lacunarity', 'Offset': 'Offset',
                'Gain': 'Gain'},
        outputs={'Fac': 'Fac'},
        props={'musgrave_type': 'Type', 'musgrave_dimensions': 'Dimensions'},
        implicit_vector='generated'),
    'ShaderNodeTexWhiteNoise': NodeSpec(
        mgraph='WhiteNoiseTexture',
        inputs={'Vector': 'Vector', 'W': 'W'},
        outputs={'Value': 'Value', 'Color': 'Color'},
        props={'noise_dimensions': 'Dimensions'},
        implicit_vector='generated'),
    'ShaderNodeTexWave': NodeSpec(
        mgraph='WaveTexture',
        inputs={'Vector': 'Vector', 'Scale': 'Scale', 'Distortion': 'Distortion',
                'Detail': 'Detail', 'Detail Scale': 'DetailScale',
                'Detail Roughness': 'DetailRoughness', 'Phase Offset': 'PhaseOffset'},
        outputs={'Fac': 'Fac', 'Color': 'Color'},
        props={'wave_type': 'Type', 'bands_direction': 'BandsDirection',
               'rings_direction': 'RingsDirection', 'wave_profile': 'Profile'},
        implicit_vector='generated'),
    'ShaderNodeTexMagic': NodeSpec(
        mgraph='MagicTexture',
        inputs={'Vector': 'Vector', 'Scale': 'Scale', 'Distortion': 'Distortion'},
        outputs={'Fac': 'Fac', 'Color': 'Color'},
        props={'turbulence_depth': 'Depth'},
        implicit_vector='generated'),
}
