"""Math family: Math, Vector Math, Map Range, Clamp (nodes/blender_math.inc, nodes/math.inc).

Mix (ShaderNodeMix by data type) and the legacy MixRGB are custom writers in the exporter;
they emit MixFloat / MixVector / MixColor with the sockets Factor, A, B, BlendType,
ClampFactor, ClampResult, NonUniform -> Result (every one of the three nodes takes all of
them; the float and vector ones ignore BlendType and ClampResult as Cycles 3.4 does).

Socket names: an mgraph node cannot have an input and an output of the same name, so Math's
output 'Value' is 'Result' and Vector Math's output 'Vector' is 'Result'. Map Range and Clamp
keep memograph's existing names (In ... Out).
"""
from ..spec import NodeSpec

NODES = {
    'ShaderNodeMath': NodeSpec(
        mgraph='Math',
        inputs={'Value': 'Value', 'Value_001': 'Value1', 'Value_002': 'Value2'},
        outputs={'Value': 'Result'},
        props={'operation': 'Operation', 'use_clamp': 'UseClamp'}),
    'ShaderNodeVectorMath': NodeSpec(
        mgraph='VectorMath',
        inputs={'Vector': 'Vector', 'Vector_001': 'Vector1', 'Vector_002': 'Vector2',
                'Scale': 'Scale'},
        outputs={'Vector': 'Result', 'Value': 'Value'},
        props={'operation': 'Operation'}),
    # data_type FLOAT writes the float sockets, FLOAT_VECTOR the *_FLOAT3 ones (the others
    # are unavailable and skipped); the float3 overload is the vector data type.
    'ShaderNodeMapRange': NodeSpec(
        mgraph='MapRange',
        inputs={'Value': 'In', 'Vector': 'In',
                'From Min': 'FromMin', 'From_Min_FLOAT3': 'FromMin',
                'From Max': 'FromMax', 'From_Max_FLOAT3': 'FromMax',
                'To Min': 'ToMin', 'To_Min_FLOAT3': 'ToMin',
                'To Max': 'ToMax', 'To_Max_FLOAT3': 'ToMax',
                'Steps': 'Steps', 'Steps_FLOAT3': 'Steps'},
        outputs={'Result': 'Out', 'Vector': 'Out'},
        props={'clamp': 'Clamped', 'interpolation_type': 'Interpolation'}),
    'ShaderNodeClamp': NodeSpec(
        mgraph='Clamp',
        inputs={'Value': 'In', 'Min': 'Min', 'Max': 'Max'},
        outputs={'Result': 'Out'},
        props={'clamp_type': 'ClampType'}),
}
