// usd_layer.cpp -- reading a USD layer with Sdf alone (usd_data.h, readLayer): the
// only source of looptess_usd that includes OpenUSD. No composition, no schema
// registry: UsdGeom's fallbacks are usd_data.h's defaults.
#include "usd_data.h"

#include <pxr/sdf/pxr.h>

#include <pxr/gf/matrix4d.h>
#include <pxr/gf/quatd.h>
#include <pxr/gf/rotation.h>
#include <pxr/gf/vec2f.h>
#include <pxr/gf/vec3d.h>
#include <pxr/gf/vec3f.h>
#include <pxr/plug/registry.h>
#include <pxr/sdf/attributeSpec.h>
#include <pxr/sdf/layer.h>
#include <pxr/sdf/primSpec.h>
#include <pxr/sdf/types.h>
#include <pxr/tf/errorMark.h>
#include <pxr/vt/array.h>
#include <pxr/vt/value.h>

#include <mutex>
#include <set>

namespace lt::usd {
namespace {

using namespace PXR_NS;

// Sdf's and Ar's plugInfo.json (fixed copies, cmake/Usd.cmake), registered once, so
// that Sdf finds its file formats with no PXR_PLUGINPATH_NAME.
void registerPlugins() {
    static std::once_flag once;
    std::call_once(once, [] {
        PlugRegistry::GetInstance().RegisterPlugins(
            std::vector<std::string>{LOOPTESS_USD_PLUGIN_DIR "/ar", LOOPTESS_USD_PLUGIN_DIR "/sdf"});
    });
}

struct Reader {
    const SdfLayerHandle layer;
    const std::string& file;
    const double* time;
    Layer& out;
    std::set<std::string> skippedTypes;

    Status fail(const SdfPath& prim, const std::string& attribute, const std::string& what) const {
        return Status::error(Status::BadInput, file + ": " + prim.GetString() +
                                                   (attribute.empty() ? "" : ": " + attribute) + ": " + what);
    }

    // The attribute's value by UsdOptions::time's rule (usd.h); empty when it has none
    // (or is blocked).
    VtValue value(const SdfPath& attr) const {
        VtValue v;
        const std::set<double> samples = layer->ListTimeSamplesForPath(attr);
        if (time && samples.count(*time))
            layer->QueryTimeSample(attr, *time, &v);
        else if (SdfAttributeSpecHandle spec = layer->GetAttributeAtPath(attr); spec && spec->HasDefaultValue())
            v = spec->GetDefaultValue();
        else if (!samples.empty()) {
            auto it = samples.begin();
            if (time) {
                auto after = samples.upper_bound(*time);
                if (after != samples.begin()) it = std::prev(after);
            }
            layer->QueryTimeSample(attr, *it, &v);
        }
        if (v.IsHolding<SdfValueBlock>()) return VtValue();
        return v;
    }

    template <class T>
    Status get(const SdfPath& prim, const std::string& name, const char* type, T& result, bool* present = nullptr) {
        if (present) *present = false;
        VtValue v = value(prim.AppendProperty(TfToken(name)));
        if (v.IsEmpty()) return Status::ok();
        if (!v.IsHolding<T>()) {
            VtValue cast = VtValue::Cast<T>(v);
            if (cast.IsEmpty()) return fail(prim, name, std::string("holds ") + v.GetTypeName() + ", not " + type);
            v = cast;
        }
        result = v.UncheckedGet<T>();
        if (present) *present = true;
        return Status::ok();
    }
    Status ints(const SdfPath& prim, const std::string& name, std::vector<int>& result, bool* present = nullptr) {
        VtArray<int> a;
        if (Status st = get(prim, name, "int[]", a, present); !st) return st;
        result.assign(a.begin(), a.end());
        return Status::ok();
    }
    Status floats(const SdfPath& prim, const std::string& name, std::vector<float>& result) {
        VtArray<float> a;
        if (Status st = get(prim, name, "float[]", a); !st) return st;
        result.assign(a.begin(), a.end());
        return Status::ok();
    }
    Status token(const SdfPath& prim, const std::string& name, std::string& result) {
        TfToken t;
        bool present = false;
        if (Status st = get(prim, name, "token", t, &present); !st) return st;
        if (present) result = t.GetString();
        return Status::ok();
    }

    template <class Vec>
    Status primvar(const SdfPrimSpecHandle& prim, const std::string& name, const char* type, Primvar& pv) {
        const SdfPath path = prim->GetPath();
        VtArray<Vec> a;
        if (Status st = get(path, name, type, a, &pv.present); !st || !pv.present) return st;
        pv.components = int(Vec::dimension);
        pv.values.resize(a.size() * Vec::dimension);
        for (size_t i = 0; i < a.size(); ++i)
            for (size_t k = 0; k < Vec::dimension; ++k) pv.values[i * Vec::dimension + k] = float(a[i][k]);
        // A field, not GetInfo: "interpolation" is UsdGeom's metadata, unknown to Sdf alone.
        VtValue interp = layer->GetField(path.AppendProperty(TfToken(name)), TfToken("interpolation"));
        // usda keeps metadata no plugin declared as an SdfUnregisteredValue (a string).
        if (interp.IsHolding<SdfUnregisteredValue>()) interp = interp.UncheckedGet<SdfUnregisteredValue>().GetValue();
        if (interp.IsHolding<TfToken>())
            pv.interpolation = interp.UncheckedGet<TfToken>().GetString();
        else if (interp.IsHolding<std::string>()) {
            pv.interpolation = interp.UncheckedGet<std::string>();  // as written: "faceVarying", quotes too
            if (pv.interpolation.size() >= 2 && pv.interpolation.front() == '"' && pv.interpolation.back() == '"')
                pv.interpolation = pv.interpolation.substr(1, pv.interpolation.size() - 2);
        } else if (!interp.IsEmpty())
            return fail(path, name, "interpolation is a " + interp.GetTypeName() + ", not a token");
        return ints(path, name + ":indices", pv.indices, &pv.indexed);
    }

    Status mesh(const SdfPrimSpecHandle& prim, MeshData& m) {
        const SdfPath p = prim->GetPath();
        m.path = p.GetString();
        VtArray<GfVec3f> points;
        Status st = get(p, "points", "point3f[]", points, &m.hasPoints);
        if (!st) return st;
        m.points.resize(points.size() * 3);
        for (size_t i = 0; i < points.size(); ++i)
            for (size_t k = 0; k < 3; ++k) m.points[i * 3 + k] = points[i][k];
        if (st = ints(p, "faceVertexCounts", m.counts, &m.hasCounts); !st) return st;
        if (st = ints(p, "faceVertexIndices", m.indices, &m.hasIndices); !st) return st;
        if (st = token(p, "subdivisionScheme", m.scheme); !st) return st;
        if (st = token(p, "interpolateBoundary", m.boundary); !st) return st;
        if (st = token(p, "orientation", m.orientation); !st) return st;
        if (st = ints(p, "creaseIndices", m.creaseIndices); !st) return st;
        if (st = ints(p, "creaseLengths", m.creaseLengths); !st) return st;
        if (st = floats(p, "creaseSharpnesses", m.creaseSharpnesses); !st) return st;
        if (st = ints(p, "cornerIndices", m.cornerIndices); !st) return st;
        if (st = floats(p, "cornerSharpnesses", m.cornerSharpnesses); !st) return st;
        if (st = ints(p, "holeIndices", m.holeIndices); !st) return st;
        if (st = primvar<GfVec2f>(prim, "primvars:st", "texCoord2f[]", m.st); !st) return st;
        return primvar<GfVec3f>(prim, "primvars:displayColor", "color3f[]", m.displayColor);
    }

    // The prim's local transform from xformOpOrder (usd.h), row vectors: the first op
    // in the order is applied last.
    Status transform(const SdfPrimSpecHandle& prim, Node& node) {
        const SdfPath p = prim->GetPath();
        VtArray<TfToken> order;
        if (Status st = get(p, "xformOpOrder", "token[]", order); !st) return st;
        GfMatrix4d m(1.0);
        for (const TfToken& t : order) {
            std::string name = t.GetString();
            if (name == "!resetXformStack!")
                return fail(p, "xformOpOrder", "!resetXformStack! is not supported (flatten the transforms first)");
            const bool invert = name.rfind("!invert!", 0) == 0;
            if (invert) name = name.substr(8);
            if (name.rfind("xformOp:", 0) != 0) return fail(p, "xformOpOrder", "\"" + name + "\" is not an xformOp");
            const size_t end = name.find(':', 8);
            const std::string kind = name.substr(8, end == std::string::npos ? end : end - 8);
            GfMatrix4d op(1.0);
            GfVec3d v(0.0);
            double angle = 0;
            GfQuatd q;
            Status st = Status::ok();
            bool present = false;
            if (kind == "translate" || kind == "scale" || (kind.rfind("rotate", 0) == 0 && kind.size() == 9)) {
                st = get(p, name, "double3", v, &present);
                if (st && present) {
                    if (kind == "translate")
                        op.SetTranslate(v);
                    else if (kind == "scale")
                        op.SetScale(v);
                    else {
                        // rotateXYZ: X first, then Y, then Z.
                        for (char axis : kind.substr(6)) {
                            const int a = axis - 'X';
                            if (a < 0 || a > 2) return fail(p, name, "not a rotation order");
                            GfVec3d dir(0.0);
                            dir[a] = 1.0;
                            op = op * GfMatrix4d(1.0).SetRotate(GfRotation(dir, v[a]));
                        }
                    }
                }
            } else if (kind == "rotateX" || kind == "rotateY" || kind == "rotateZ") {
                st = get(p, name, "double", angle, &present);
                GfVec3d dir(0.0);
                dir[kind[6] - 'X'] = 1.0;
                if (st && present) op.SetRotate(GfRotation(dir, angle));
            } else if (kind == "orient") {
                st = get(p, name, "quatd", q, &present);
                if (st && present) op.SetRotate(q);
            } else if (kind == "transform") {
                st = get(p, name, "matrix4d", op, &present);
            } else {
                return fail(p, "xformOpOrder", "op \"" + kind + "\" is not supported");
            }
            if (!st) return st;
            if (!present) return fail(p, name, "in xformOpOrder but has no value");
            if (invert) op = op.GetInverse();
            m = op * m;
        }
        if (m == GfMatrix4d(1.0)) return Status::ok();
        node.hasMatrix = true;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) node.matrix[r * 4 + c] = m[r][c];
        return Status::ok();
    }

    // `prim` and its children as nodes; returns the node's index, or -1 when skipped.
    Status visit(const SdfPrimSpecHandle& prim, int& index) {
        index = -1;
        const SdfPath p = prim->GetPath();
        if (prim->HasReferences() || prim->HasPayloads() || prim->HasInheritPaths() || prim->HasSpecializes() ||
            prim->HasVariantSetNames()) {
            const char* what = prim->HasReferences()     ? "references"
                               : prim->HasPayloads()     ? "payloads"
                               : prim->HasInheritPaths() ? "inherits"
                               : prim->HasSpecializes()  ? "specializes"
                                                         : "variant sets";
            return fail(p, "",
                        std::string("uses composition (") + what +
                            "), which loopbake does not read; flatten it first: usdcat --flatten IN -o OUT.usdc");
        }
        if (prim->GetSpecifier() != SdfSpecifierDef) return Status::ok();  // over, class: nothing without composition
        const std::string type = prim->GetTypeName().GetString();
        if (type != "Mesh" && type != "Xform" && type != "Scope" && !type.empty()) {
            if (skippedTypes.insert(type).second)
                out.warnings.push_back(file + ": prims of type " + type + " are skipped with their children (first " +
                                       p.GetString() + ")");
            return Status::ok();
        }
        Node node;
        node.name = prim->GetName();
        if (type != "Scope")
            if (Status st = transform(prim, node); !st) return st;
        if (type == "Mesh") {
            MeshData m;
            if (Status st = mesh(prim, m); !st) return st;
            node.mesh = int(out.meshes.size());
            out.meshes.push_back(std::move(m));
        }
        index = int(out.nodes.size());
        out.nodes.push_back(std::move(node));
        for (const SdfPrimSpecHandle& child : prim->GetNameChildren()) {
            int c = -1;
            if (Status st = visit(child, c); !st) return st;
            if (c >= 0) out.nodes[size_t(index)].children.push_back(c);
        }
        return Status::ok();
    }
};

std::string errors(const TfErrorMark& mark) {
    std::string text;
    for (auto it = mark.GetBegin(); it != mark.GetEnd(); ++it) {
        if (!text.empty()) text += "; ";
        text += it->GetCommentary();
    }
    return text.size() > 300 ? text.substr(0, 300) + "..." : text;
}

}  // namespace

Status readLayer(const std::string& path, const double* time, Layer& layer) {
    registerPlugins();
    layer = Layer{};
    TfErrorMark mark;
    SdfLayerRefPtr sdf = SdfLayer::OpenAsAnonymous(path);
    if (!sdf || !mark.IsClean()) {
        Status st = Status::error(Status::BadInput, path + ": not a USD layer Sdf can read" +
                                                        (mark.IsClean() ? std::string() : " (" + errors(mark) + ")"));
        mark.Clear();
        return st;
    }
    if (!sdf->GetSubLayerPaths().empty())
        return Status::error(Status::BadInput,
                             path +
                                 ": uses composition (subLayers), which loopbake does not read; flatten it "
                                 "first: usdcat --flatten IN -o OUT.usdc");
    VtValue up = sdf->GetField(SdfPath::AbsoluteRootPath(), TfToken("upAxis"));
    layer.zUp = up.IsHolding<TfToken>() && up.UncheckedGet<TfToken>() == "Z";
    Reader reader{sdf, path, time, layer, {}};
    Status st = Status::ok();
    for (const SdfPrimSpecHandle& prim : sdf->GetRootPrims()) {
        int index = -1;
        if (st = reader.visit(prim, index); !st) break;
        if (index >= 0) layer.roots.push_back(index);
    }
    if (st && !mark.IsClean())
        st = Status::error(Status::BadInput, path + ": Sdf could not read every value (" + errors(mark) + ")");
    mark.Clear();
    return st;
}

}  // namespace lt::usd
