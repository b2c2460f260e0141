# Writes a 1 x 2 x 3 in block as STEP text in the habits of other systems' exporters, not
# OpenCASCADE's: inch units by CONVERSION_BASED_UNIT, an ADVANCED_BREP_SHAPE_REPRESENTATION with a
# MANIFOLD_SOLID_BREP of six planar ADVANCED_FACEs, and
#   ap203: Creo/Pro-E's AP203 (CONFIG_CONTROL_DESIGN, MECHANICAL_CONTEXT, DESIGN_CONTEXT);
#   ap242: an AP242 header and contexts (PRODUCT_CONTEXT, PRODUCT_DEFINITION_CONTEXT), the edges
#          written the other way round (ORIENTED_EDGE .F. where AP203 has .T.).
#   python3 make_blocks.py ap203|ap242 OUT.stp
import sys
schema = sys.argv[1]
a, b, c = 1.0, 2.0, 3.0
ents = []
def e(text):
    ents.append(text)
    return "#%d" % len(ents)
def pt(p): return e("CARTESIAN_POINT('',(%.6f,%.6f,%.6f))" % p)
def d(v): return e("DIRECTION('',(%.6f,%.6f,%.6f))" % v)
if schema == "ap203":
    ctx = e("APPLICATION_CONTEXT('configuration controlled 3d designs of mechanical parts and assemblies')")
    e("APPLICATION_PROTOCOL_DEFINITION('international standard','config_control_design',1994,%s)" % ctx)
    mctx = e("MECHANICAL_CONTEXT('',%s,'mechanical')" % ctx)
else:
    ctx = e("APPLICATION_CONTEXT('managed model based 3d engineering')")
    e("APPLICATION_PROTOCOL_DEFINITION('international standard','ap242_managed_model_based_3d_engineering',2014,%s)" % ctx)
    mctx = e("PRODUCT_CONTEXT('part definition',%s,'mechanical')" % ctx)
prod = e("PRODUCT('BLOCK','BLOCK','NOT SPECIFIED',(%s))" % mctx)
pdf = e("PRODUCT_DEFINITION_FORMATION_WITH_SPECIFIED_SOURCE('1','LAST_VERSION',%s,.MADE.)" % prod)
dctx = e(("DESIGN_CONTEXT('detailed design',%s,'design')" if schema == "ap203" else
          "PRODUCT_DEFINITION_CONTEXT('part definition',%s,'design')") % ctx)
pd = e("PRODUCT_DEFINITION('design','',%s,%s)" % (pdf, dctx))
pds = e("PRODUCT_DEFINITION_SHAPE('','SHAPE FOR BLOCK.',%s)" % pd)
mm = e("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))")
lm = e("LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),%s)" % mm)
dims = e("DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.)")
inch = e("(CONVERSION_BASED_UNIT('INCH',%s)LENGTH_UNIT()NAMED_UNIT(%s))" % (lm, dims))
rad = e("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))")
sr = e("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())")
unc = e("UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(0.0001),%s,'distance_accuracy_value','EDGE CURVE AND VERTEX POINT ACCURACY')" % inch)
gctx = e("(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((%s))GLOBAL_UNIT_ASSIGNED_CONTEXT((%s,%s,%s))REPRESENTATION_CONTEXT('ID1','3D'))" % (unc, inch, rad, sr))
# The block's corners, edges and faces.
P = {}
for i, x in enumerate((0.0, a)):
    for j, y in enumerate((0.0, b)):
        for k, z in enumerate((0.0, c)):
            P[(i, j, k)] = ((x, y, z), None)
V = {}
for key, (p, _) in P.items():
    V[key] = e("VERTEX_POINT('',%s)" % pt(p))
E = {}
def edge(k1, k2):
    if (k1, k2) in E: return E[(k1, k2)], True
    if (k2, k1) in E: return E[(k2, k1)], False
    if schema == "ap242":
        ed, _ = edge_new(k2, k1)
        return ed, False
    return edge_new(k1, k2)
def edge_new(k1, k2):
    p1, p2 = P[k1][0], P[k2][0]
    dv = tuple(q - p for p, q in zip(p1, p2))
    L = max(abs(x) for x in dv)
    line = e("LINE('',%s,%s)" % (pt(p1), e("VECTOR('',%s,%.6f)" % (d(tuple(x / L for x in dv)), L))))
    E[(k1, k2)] = e("EDGE_CURVE('',%s,%s,%s,.T.)" % (V[k1], V[k2], line))
    return E[(k1, k2)], True
# Each face: its corners counter-clockwise seen from outside, its outward normal and a reference direction.
faces = [
    ([(0,0,0),(0,1,0),(1,1,0),(1,0,0)], (0,0,-1), (1,0,0), (0,0,0)),
    ([(0,0,1),(1,0,1),(1,1,1),(0,1,1)], (0,0,1), (1,0,0), (0,0,c)),
    ([(0,0,0),(1,0,0),(1,0,1),(0,0,1)], (0,-1,0), (1,0,0), (0,0,0)),
    ([(0,1,0),(0,1,1),(1,1,1),(1,1,0)], (0,1,0), (1,0,0), (0,b,0)),
    ([(0,0,0),(0,0,1),(0,1,1),(0,1,0)], (-1,0,0), (0,1,0), (0,0,0)),
    ([(1,0,0),(1,1,0),(1,1,1),(1,0,1)], (1,0,0), (0,1,0), (a,0,0)),
]
F = []
for corners, n, ref, origin in faces:
    oes = []
    for q in range(4):
        ed, same = edge(corners[q], corners[(q + 1) % 4])
        oes.append(e("ORIENTED_EDGE('',*,*,%s,%s)" % (ed, ".T." if same else ".F.")))
    loop = e("EDGE_LOOP('',(%s))" % ",".join(oes))
    bound = e("FACE_OUTER_BOUND('',%s,.T.)" % loop)
    plane = e("PLANE('',%s)" % e("AXIS2_PLACEMENT_3D('',%s,%s,%s)" % (pt(origin), d(n), d(ref))))
    F.append(e("ADVANCED_FACE('',(%s),%s,.T.)" % (bound, plane)))
shell = e("CLOSED_SHELL('',(%s))" % ",".join(F))
brep = e("MANIFOLD_SOLID_BREP('BLOCK',%s)" % shell)
origin = e("AXIS2_PLACEMENT_3D('',%s,%s,%s)" % (pt((0, 0, 0)), d((0, 0, 1)), d((1, 0, 0))))
rep = e("ADVANCED_BREP_SHAPE_REPRESENTATION('BLOCK',(%s,%s),%s)" % (brep, origin, gctx))
e("SHAPE_DEFINITION_REPRESENTATION(%s,%s)" % (pds, rep))
e("PRODUCT_RELATED_PRODUCT_CATEGORY('detail',$,(%s))" % prod)
out = ["ISO-10303-21;", "HEADER;",
       "FILE_DESCRIPTION(('a 1 x 2 x 3 in block'),'2;1');",
       "FILE_NAME('BLOCK.STP','2026-12-03T00:00:00',('massprops'),(''),'%s','%s','');" %
       (("CREO PARAMETRIC BY PTC INC, 2011280",) * 2 if schema == "ap203" else ("CATIA Version 5 Release 30",) * 2),
       "FILE_SCHEMA(('CONFIG_CONTROL_DESIGN'));" if schema == "ap203" else
       "FILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }'));",
       "ENDSEC;", "DATA;"]
out += ["#%d=%s;" % (i + 1, t) for i, t in enumerate(ents)]
out += ["ENDSEC;", "END-ISO-10303-21;"]
open(sys.argv[2], "w").write("\n".join(out) + "\n")
