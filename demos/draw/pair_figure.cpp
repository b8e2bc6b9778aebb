#include "demos/draw/pair_figure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "render/legibility.h"

namespace cdlab::demos {

using namespace render;

Camera panelCamera(bool planar, const Vec3& center, double radius, const Vec3& view, const TwoPanelLayout& layout) {
    if (planar) {
        const double aspect = double(layout.panelWidth()) / layout.panelHeight();
        // Fit the circle in the shorter side with a margin for labels, and leave room for the heading.
        const double height = std::max(2.0 * radius, 2.0 * radius / aspect) * 1.3;
        return Camera::twoD(center.x(), center.y() + 0.04 * height, height);
    }
    return framingCamera(center, radius * 1.05, view, Vec3::UnitY(), true);
}

Camera acrossGapCamera(GlContext& gl, const CanvasOptions& options, const Camera& base, const PairDrawing& d,
                       const Vec3& pa, const Vec3& pb) {
    const Vec3 gap = pb - pa;
    if (d.planar || !(gap.norm() > 0) || base.projection != Camera::Projection::Perspective) return base;
    // The bodies alone through `base`: apart on the picture already?
    Canvas probe(gl, options, base);
    probe.noteBody("A", d.a.vertices, "B");
    probe.noteBody("B", d.b.vertices, "A");
    const FigureLayout layout = probe.layout();
    const std::vector<LegibilityProblem> problems = checkLegibility(layout, options.width, options.height);
    if (std::none_of(problems.begin(), problems.end(), [](const LegibilityProblem& p) {
            return p.kind == LegibilityKind::SeparatedBodiesOverlap;
        }))
        return base;
    // The same distance and field of view, the view turned flat to the gap, the target (and so
    // the eye) moved into the plane midway between the closest points.
    const Vec3 n = gap.normalized(), mid = 0.5 * (pa + pb);
    Vec3 view = base.eye - base.target;
    const double distance = view.norm();
    view -= view.dot(n) * n;
    if (view.norm() < 1e-9 * distance) view = n.unitOrthogonal();
    Camera cam = base;
    cam.target = base.target - (base.target - mid).dot(n) * n;
    cam.eye = cam.target + view.normalized() * distance;
    if (std::abs(cam.up.normalized().dot(view.normalized())) > 0.99) cam.up = n;
    return cam;
}

void drawPanelHeading(Canvas& canvas, const std::string& heading, const std::string& sub) {
    canvas.drawTextPx(14, 10, heading, TextStyle{20.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    if (!sub.empty())
        canvas.drawTextPx(14, 38, sub,
                          TextStyle{17.0f, roleColor(Role::Highlight).scaled(0.8f), Anchor::TopLeft, true, true});
}

TwoPanelLayout twoPanelLayout(int width, int height, const std::string& sceneCaption) {
    TwoPanelLayout layout{width, height};
    if (!sceneCaption.empty()) layout.captionBand += 25;
    return layout;
}

Image composeTwoPanel(GlContext& gl, const TwoPanelLayout& layout, int scale, const std::string& title,
                      const std::string& sceneCaption, const Image& left, const Image& right,
                      const std::vector<std::string>& captionLines) {
    Canvas canvas(gl, canvasOptions(layout.width, layout.height, scale), Camera::twoD(0, 0, 1));
    canvas.drawTextPx(18, 10, title, TextStyle{24.0f, roleColor(Role::Ink), Anchor::TopLeft, true, true});
    const double lineH = 25.0;
    double y = layout.height - layout.captionBand + 8;
    if (!sceneCaption.empty()) {  // the scene's caption first, in a quieter ink, as on every frame
        canvas.drawTextPx(18, y, sceneCaption,
                          TextStyle{17.0f, roleColor(Role::Ink).mixed(roleColor(Role::Muted), 0.5f), Anchor::TopLeft,
                                    false, false});
        y += lineH;
    }
    for (const std::string& line : captionLines) {
        canvas.drawTextPx(18, y, line, TextStyle{17.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        y += lineH;
    }
    Image frame = canvas.readPixels();
    blit(frame, left, 0, layout.titleBand);
    blit(frame, right, layout.panelWidth(), layout.titleBand);
    // A 2-pixel rule between the panels.
    paintRect(frame, layout.panelWidth() - 1, layout.titleBand, 2, layout.panelHeight(), roleColor(Role::Muted));
    return frame;
}

PairDrawing makePairDrawing(const PairScene& pair, bool drawMinkowski, std::vector<Vec3> csPoints,
                            std::vector<std::string>& skipped) {
    PairDrawing d;
    d.planar = pair.dimension == 2;
    d.a = shapeDrawable(pair.a);
    d.b = shapeDrawable(pair.b);
    if (drawMinkowski) d.c = minkowskiDrawable(pair.a, pair.b, &d.exact);
    else skipped.push_back("Minkowski difference hull (no 'minkowski' layer)");
    if (d.c.valid) csPoints.insert(csPoints.end(), d.c.vertices.begin(), d.c.vertices.end());
    csPoints.push_back(Vec3::Zero());
    boundingSphere(csPoints, d.cCenter, d.cRadius);
    std::vector<Vec3> wpts = d.a.vertices;
    wpts.insert(wpts.end(), d.b.vertices.begin(), d.b.vertices.end());
    boundingSphere(wpts, d.wCenter, d.wRadius);
    return d;
}

void drawSupportPoint(Canvas& canvas, const ConvexDrawable& body, const Vec3& point, float radiusPx) {
    const bool hidden = behindBody(canvas.camera(), point, facePlanes(body), 1e-3 * body.radius);
    const auto faded = [&](const Color& c) { return hidden ? c.mixed(roleColor(Role::Background), 0.55f) : c; };
    canvas.drawPoint(point, radiusPx, faded(roleColor(Role::Support)), true, 1.5f, faded(roleColor(Role::Ink)));
}

void drawPairBodies(Canvas& world, const PairDrawing& d, float alpha3d, bool colliding, bool labels, bool apart) {
    const float alpha = d.planar ? 0.35f : alpha3d;
    for (const auto& [body, role] : {std::pair{&d.a, Role::ShapeA}, std::pair{&d.b, Role::ShapeB}}) {
        const char* name = role == Role::ShapeA ? "A" : "B";
        world.setStrokeOwner(bodyOwner(name));
        drawBody(world, *body, roleColor(role), alpha,
                 colliding ? roleColor(Role::Colliding) : roleColor(role).scaled(0.6f), colliding ? 3.5f : 2.0f);
        world.noteBody(name, body->planar && !body->outline.empty() ? body->outline : body->vertices,
                       apart ? (role == Role::ShapeA ? "B" : "A") : "");
    }
    world.setStrokeOwner(0);
    if (!labels) return;
    const auto [nameA, nameB] = bodyNamePoints(d.a, d.b);
    drawBodyName(world, nameA, "A", Role::ShapeA);
    drawBodyName(world, nameB, "B", Role::ShapeB);
    // The key only where outlines are drawn (polytopes, 2D shapes; curved 3D bodies have none).
    if (colliding && (d.planar || !d.a.edges.empty() || !d.b.edges.empty()))
        drawKey(world, 14, 64, {{roleColor(Role::Colliding), "colliding: A and B share a point"}});  // touching too
}

}  // namespace cdlab::demos
