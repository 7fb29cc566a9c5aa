"""Writes, as C++, the Pinocchio models that `buildModelFromUrdf` reads from the
robots in `robots/`: one function per robot adding the same joints (type,
axis, placement) and bodies (mass, centre of mass, inertia) with every number
printed to 17 digits. The PyPI wheel `pin` ships the URDF parser's library but
not urdfdom's headers, so `urdf.cpp` builds the models this way.

    python3 urdf_model.py ROBOTS_DIR OUT.hpp
"""
import sys
import pinocchio as pin


def vec(v):
    return ", ".join(repr(float(x)) for x in v)


def mat(m):
    return ", ".join(repr(float(m[i, j])) for i in range(3) for j in range(3))


def joint(j):
    name = j.shortname()
    simple = {"JointModelRX", "JointModelRY", "JointModelRZ", "JointModelPX", "JointModelPY", "JointModelPZ"}
    if name in simple:
        return f"pin::{name}()"
    if name in ("JointModelRevoluteUnaligned", "JointModelPrismaticUnaligned"):
        return f"pin::{name}(Eigen::Vector3d({vec(j.extract().axis)}))"
    raise SystemExit(f"joint type {name} not written")


def model_function(fn, model):
    out = [f"static pin::Model {fn}() {{", "  pin::Model model;", f'  model.name = "{model.name}";']
    for i in range(1, model.njoints):
        p = model.jointPlacements[i]
        inertia = model.inertias[i]
        out.append(
            f"  {{ Eigen::Matrix3d R; R << {mat(p.rotation)};\n"
            f"    pin::JointIndex j = model.addJoint({model.parents[i]}, {joint(model.joints[i])}, "
            f'pin::SE3(R, Eigen::Vector3d({vec(p.translation)})), "{model.names[i]}");\n'
            f"    Eigen::Matrix3d I; I << {mat(inertia.inertia)};\n"
            f"    model.appendBodyToJoint(j, pin::Inertia({float(inertia.mass)!r}, "
            f"Eigen::Vector3d({vec(inertia.lever)}), I)); }}"
        )
    out += ["  return model;", "}"]
    return "\n".join(out)


robots, target = sys.argv[1], sys.argv[2]
with open(target, "w") as f:
    f.write("// Written by urdf_model.py from the URDF files in robots/.\n")
    for fn, file in [("ur5", "ur5.urdf"), ("panda", "panda.urdf")]:
        f.write(model_function(fn, pin.buildModelFromUrdf(f"{robots}/{file}")) + "\n\n")
