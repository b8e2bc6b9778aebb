#include "render/color.h"

namespace cdlab::render {

namespace {
// Okabe & Ito, "Color Universal Design" (2008), as 0..1 sRGB.
constexpr Color kOrange{0.902f, 0.624f, 0.000f, 1};
constexpr Color kSkyBlue{0.337f, 0.706f, 0.914f, 1};
constexpr Color kBluishGreen{0.000f, 0.620f, 0.451f, 1};
constexpr Color kYellow{0.941f, 0.894f, 0.259f, 1};
constexpr Color kBlue{0.000f, 0.447f, 0.698f, 1};
constexpr Color kVermillion{0.835f, 0.369f, 0.000f, 1};
constexpr Color kReddishPurple{0.800f, 0.475f, 0.655f, 1};
constexpr Color kBlack{0, 0, 0, 1};
}  // namespace

Color roleColor(Role role) {
    switch (role) {
        case Role::Background: return {1, 1, 1, 1};
        case Role::Ink: return {0.10f, 0.10f, 0.12f, 1};
        case Role::Muted: return {0.62f, 0.62f, 0.65f, 1};
        case Role::ShapeA: return kBlue;
        case Role::ShapeB: return kOrange;
        case Role::Minkowski: return kSkyBlue;
        case Role::Simplex: return kBluishGreen;
        case Role::Origin: return kBlack;
        case Role::Direction: return kReddishPurple;
        case Role::Support: return kVermillion;
        case Role::Highlight: return kVermillion;
        case Role::Query: return kBlack;
        case Role::Result: return kVermillion;
        // Wine: darker than vermillion and orange (told apart by lightness too, for colour-blind
        // readers), used only for the outline of intersecting bodies.
        case Role::Colliding: return {0.55f, 0.07f, 0.30f, 1};
    }
    return kBlack;
}

Color categorical(int index) {
    static constexpr Color kCycle[] = {kOrange, kSkyBlue, kBluishGreen, kYellow, kBlue, kVermillion, kReddishPurple};
    constexpr int n = sizeof(kCycle) / sizeof(kCycle[0]);
    return kCycle[((index % n) + n) % n];
}

}  // namespace cdlab::render
