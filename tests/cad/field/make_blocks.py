# Writes blocks as STEP text in the habits of other systems' exporters, not OpenCASCADE's: units
# by SI_UNIT or CONVERSION_BASED_UNIT, ADVANCED_BREP_SHAPE_REPRESENTATIONs of MANIFOLD_SOLID_BREPs
# with six planar ADVANCED_FACEs each.
#   ap203: a 1 x 2 x 3 in block in Creo/Pro-E's AP203 (CONFIG_CONTROL_DESIGN, MECHANICAL_CONTEXT,
#          DESIGN_CONTEXT), inches by CONVERSION_BASED_UNIT;
#   ap242: the same block with an AP242 header and contexts (PRODUCT_CONTEXT,
#          PRODUCT_DEFINITION_CONTEXT), the edges written the other way round (ORIENTED_EDGE .F.);
#   mixed: an AP203 assembly in millimetres of two parts whose representations declare different
#          units: the inch block placed at x = 100 mm, and a 10 x 20 x 30 mm block at the origin
#          (NEXT_ASSEMBLY_USAGE_OCCURRENCE, CONTEXT_DEPENDENT_SHAPE_REPRESENTATION).
#   python3 make_blocks.py ap203|ap242|mixed OUT.stp
import sys

schema = sys.argv[1]
ents = []


def e(text):
    ents.append(text)
    return "#%d" % len(ents)


def pt(p):
    return e("CARTESIAN_POINT('',(%.6f,%.6f,%.6f))" % p)


def d(v):
    return e("DIRECTION('',(%.6f,%.6f,%.6f))" % v)


def axis(origin):
    return e("AXIS2_PLACEMENT_3D('',%s,%s,%s)" % (pt(origin), d((0, 0, 1)), d((1, 0, 0))))


if schema == "ap242":
    ctx = e("APPLICATION_CONTEXT('managed model based 3d engineering')")
    e("APPLICATION_PROTOCOL_DEFINITION('international standard','ap242_managed_model_based_3d_engineering',2014,%s)"
      % ctx)
    mctx = e("PRODUCT_CONTEXT('part definition',%s,'mechanical')" % ctx)
    dctx = e("PRODUCT_DEFINITION_CONTEXT('part definition',%s,'design')" % ctx)
else:
    ctx = e("APPLICATION_CONTEXT('configuration controlled 3d designs of mechanical parts and assemblies')")
    e("APPLICATION_PROTOCOL_DEFINITION('international standard','config_control_design',1994,%s)" % ctx)
    mctx = e("MECHANICAL_CONTEXT('',%s,'mechanical')" % ctx)
    dctx = e("DESIGN_CONTEXT('detailed design',%s,'design')" % ctx)
mm = e("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))")
rad = e("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))")
sr = e("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())")


def context(unit):
    unc = e("UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(0.0001),%s,'distance_accuracy_value',"
            "'EDGE CURVE AND VERTEX POINT ACCURACY')" % unit)
    return e("(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((%s))"
             "GLOBAL_UNIT_ASSIGNED_CONTEXT((%s,%s,%s))REPRESENTATION_CONTEXT('ID1','3D'))" % (unc, unit, rad, sr))


def inch_unit():
    lm = e("LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),%s)" % mm)
    dims = e("DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.)")
    return e("(CONVERSION_BASED_UNIT('INCH',%s)LENGTH_UNIT()NAMED_UNIT(%s))" % (lm, dims))


def product(name):
    prod = e("PRODUCT('%s','%s','NOT SPECIFIED',(%s))" % (name, name, mctx))
    e("PRODUCT_RELATED_PRODUCT_CATEGORY('detail',$,(%s))" % prod)
    pdf = e("PRODUCT_DEFINITION_FORMATION_WITH_SPECIFIED_SOURCE('1','LAST_VERSION',%s,.MADE.)" % prod)
    pd = e("PRODUCT_DEFINITION('design','',%s,%s)" % (pdf, dctx))
    return pd, e("PRODUCT_DEFINITION_SHAPE('','SHAPE FOR %s.',%s)" % (name, pd))


def block(name, a, b, c, gctx, reversed_edges):
    """An a x b x c block with a corner at the origin of its representation; returns the
    representation and its origin's axis placement."""
    P = {(i, j, k): (x, y, z) for i, x in enumerate((0.0, a)) for j, y in enumerate((0.0, b))
         for k, z in enumerate((0.0, c))}
    V = {key: e("VERTEX_POINT('',%s)" % pt(p)) for key, p in P.items()}
    E = {}

    def new_edge(k1, k2):
        p1, p2 = P[k1], P[k2]
        dv = tuple(q - p for p, q in zip(p1, p2))
        L = max(abs(x) for x in dv)
        line = e("LINE('',%s,%s)" % (pt(p1), e("VECTOR('',%s,%.6f)" % (d(tuple(x / L for x in dv)), L))))
        E[(k1, k2)] = e("EDGE_CURVE('',%s,%s,%s,.T.)" % (V[k1], V[k2], line))

    def edge(k1, k2):  # the edge from k1 to k2, and whether it runs that way
        if (k1, k2) not in E and (k2, k1) not in E:
            new_edge(*((k2, k1) if reversed_edges else (k1, k2)))
        return (E[(k1, k2)], True) if (k1, k2) in E else (E[(k2, k1)], False)

    # Each face: its corners counter-clockwise seen from outside, its outward normal, a reference
    # direction in it and a point of it.
    faces = [
        ([(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)], (0, 0, -1), (1, 0, 0), (0, 0, 0)),
        ([(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)], (0, 0, 1), (1, 0, 0), (0, 0, c)),
        ([(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)], (0, -1, 0), (1, 0, 0), (0, 0, 0)),
        ([(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)], (0, 1, 0), (1, 0, 0), (0, b, 0)),
        ([(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)], (-1, 0, 0), (0, 1, 0), (0, 0, 0)),
        ([(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)], (1, 0, 0), (0, 1, 0), (a, 0, 0)),
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
    brep = e("MANIFOLD_SOLID_BREP('%s',%s)" % (name, e("CLOSED_SHELL('',(%s))" % ",".join(F))))
    origin = axis((0, 0, 0))
    return e("ADVANCED_BREP_SHAPE_REPRESENTATION('%s',(%s,%s),%s)" % (name, brep, origin, gctx)), origin


if schema in ("ap203", "ap242"):
    pd, pds = product("BLOCK")
    rep, _ = block("BLOCK", 1.0, 2.0, 3.0, context(inch_unit()), schema == "ap242")
    e("SHAPE_DEFINITION_REPRESENTATION(%s,%s)" % (pds, rep))
else:  # mixed: an assembly in mm of an inch part and a mm part
    mm_ctx = context(mm)
    asm_pd, asm_pds = product("ASSEMBLY")
    asm_origin, at_inch, at_mm = axis((0, 0, 0)), axis((100, 0, 0)), axis((0, 0, 0))
    asm_rep = e("SHAPE_REPRESENTATION('ASSEMBLY',(%s,%s,%s),%s)" % (asm_origin, at_inch, at_mm, mm_ctx))
    e("SHAPE_DEFINITION_REPRESENTATION(%s,%s)" % (asm_pds, asm_rep))
    for k, (name, size, gctx, placed) in enumerate([("INCH_BLOCK", (1.0, 2.0, 3.0), context(inch_unit()), at_inch),
                                                    ("MM_BLOCK", (10.0, 20.0, 30.0), mm_ctx, at_mm)]):
        pd, pds = product(name)
        rep, origin = block(name, *size, gctx, False)
        e("SHAPE_DEFINITION_REPRESENTATION(%s,%s)" % (pds, rep))
        nauo = e("NEXT_ASSEMBLY_USAGE_OCCURRENCE('%d','%s:1','',%s,%s,$)" % (k + 1, name, asm_pd, pd))
        use = e("PRODUCT_DEFINITION_SHAPE('Placement','Placement of an item',%s)" % nauo)
        transform = e("ITEM_DEFINED_TRANSFORMATION('','',%s,%s)" % (origin, placed))
        link = e("(REPRESENTATION_RELATIONSHIP('','',%s,%s)REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(%s)"
                 "SHAPE_REPRESENTATION_RELATIONSHIP())" % (rep, asm_rep, transform))
        e("CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(%s,%s)" % (link, use))

system = "CATIA Version 5 Release 30" if schema == "ap242" else "CREO PARAMETRIC BY PTC INC, 2011280"
out = ["ISO-10303-21;", "HEADER;",
       "FILE_DESCRIPTION(('blocks of known mass properties'),'2;1');",
       "FILE_NAME('BLOCK.STP','2026-12-03T00:00:00',('massprops'),(''),'%s','%s','');" % (system, system),
       "FILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }'));" if schema == "ap242"
       else "FILE_SCHEMA(('CONFIG_CONTROL_DESIGN'));",
       "ENDSEC;", "DATA;"]
out += ["#%d=%s;" % (i + 1, t) for i, t in enumerate(ents)]
out += ["ENDSEC;", "END-ISO-10303-21;"]
with open(sys.argv[2], "w") as f:
    f.write("\n".join(out) + "\n")
