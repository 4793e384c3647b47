// MGF colours: CIE xyY to linear RGB (Rec. 709 primaries, white E) and back, spectra and
// black bodies to chromaticity, and the material conversion (rd, ed, sides, rs/ts/td).
#include "solver/scene/mgf_color.h"

#include <algorithm>

#include "gtest/gtest.h"
#include "solver/scene/mgf_material.h"

namespace radflux {
namespace {

TEST(MgfColor, NeutralMapsToEqualRgb) {
  const Rgb rgb = XyYToLinearRgb(MgfColor{}, 0.6);
  for (double v : rgb) EXPECT_NEAR(v, 0.6, 1e-12);
}

TEST(MgfColor, PrimariesMapToSingleBands) {
  const MgfColor primaries[3] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  for (int c = 0; c < 3; ++c) {
    const Rgb rgb = XyYToLinearRgb(primaries[c], 0.5);
    for (int b = 0; b < 3; ++b) {
      if (b == c)
        EXPECT_GT(rgb[b], 0.1);
      else
        EXPECT_NEAR(rgb[b], 0, 1e-12);
    }
  }
}

TEST(MgfColor, SpectralGreenIsOutOfGamutWithNegativeRedAndBlue) {
  // 520 nm on the spectral locus.
  absl::StatusOr<MgfColor> c = SpectrumChromaticity(510, 530, {0, 1, 0});
  ASSERT_TRUE(c.ok());
  EXPECT_NEAR(c->x, 0.0743, 1e-4);
  EXPECT_NEAR(c->y, 0.8338, 1e-4);
  const Rgb rgb = XyYToLinearRgb(*c, 1);
  EXPECT_LT(rgb[0], 0);
  EXPECT_GT(rgb[1], 0);
  EXPECT_LT(rgb[2], 0);
}

TEST(MgfColor, RoundTrip) {
  for (const MgfColor& c : {MgfColor{0.31, 0.33}, MgfColor{0.5, 0.35}, MgfColor{0.25, 0.2}}) {
    double y = 0;
    const MgfColor back = LinearRgbToXyY(XyYToLinearRgb(c, 0.37), &y);
    EXPECT_NEAR(back.x, c.x, 1e-12);
    EXPECT_NEAR(back.y, c.y, 1e-12);
    EXPECT_NEAR(y, 0.37, 1e-12);
  }
}

TEST(MgfColor, EqualEnergySpectrumIsWhiteE) {
  absl::StatusOr<MgfColor> c = SpectrumChromaticity(380, 780, std::vector<double>(41, 0.5));
  ASSERT_TRUE(c.ok());
  EXPECT_NEAR(c->x, 1.0 / 3, 5e-4);
  EXPECT_NEAR(c->y, 1.0 / 3, 5e-4);
  // A finely sampled flat spectrum gives the same.
  absl::StatusOr<MgfColor> fine = SpectrumChromaticity(380, 780, std::vector<double>(401, 2));
  ASSERT_TRUE(fine.ok());
  EXPECT_NEAR(fine->x, 1.0 / 3, 5e-4);
}

TEST(MgfColor, BlackBodyAt2856KIsIlluminantA) {
  absl::StatusOr<MgfColor> a = BlackbodyChromaticity(2856);
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(a->x, 0.4476, 1e-3);
  EXPECT_NEAR(a->y, 0.4074, 1e-3);
  absl::StatusOr<MgfColor> hot = BlackbodyChromaticity(10000);
  ASSERT_TRUE(hot.ok());
  EXPECT_LT(hot->x, a->x);  // hotter is bluer
  EXPECT_FALSE(BlackbodyChromaticity(500).ok());
  EXPECT_FALSE(SpectrumChromaticity(800, 900, {1, 1}).ok());  // nothing visible
  EXPECT_FALSE(SpectrumChromaticity(400, 400, {1, 1}).ok());
}

TEST(MgfColor, MixAddsTristimulusValues) {
  const MgfColor a{0.6, 0.3}, b{0.2, 0.5};
  const MgfColor m = MixColors({1, 3}, {a, b});
  // X + Y + Z of a colour with luminance w is w / y.
  const double sa = 1 / a.y, sb = 3 / b.y;
  EXPECT_NEAR(m.x, (sa * a.x + sb * b.x) / (sa + sb), 1e-12);
  EXPECT_NEAR(m.y, (1 + 3) / (sa + sb), 1e-12);
}

TEST(MgfMaterial, ConversionOfValuesAndLeftOutParts) {
  MgfMaterialContext ctx;
  for (const std::vector<std::string>& w :
       std::vector<std::vector<std::string>>{{"m", "lamp", "="},
                                             {"rd", "0.25"},
                                             {"ed", "179"},
                                             {"sides", "1"},
                                             {"rs", "0.1", "0.05"},
                                             {"td", "0.2"}}) {
    ASSERT_TRUE(ctx.Apply(w).ok()) << w[0];
  }
  Scene scene;
  const uint32_t index = ctx.Intern(scene, "x.mgf:7");
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[index];
  EXPECT_EQ(m.name, "lamp");
  EXPECT_FALSE(m.two_sided);
  for (int b = 0; b < 3; ++b) {
    EXPECT_NEAR(m.reflectance[b], 0.25, 1e-12);
    EXPECT_NEAR(m.emission[b], 1.0, 1e-12);  // 179 lm/m^2 of white is 1 W/m^2 per band
  }
  ASSERT_EQ(scene.import_log.fixups().size(), 2u);
  EXPECT_EQ(scene.import_log.fixups()[0].kind, "mgf_specular_reflection_left_out");
  EXPECT_EQ(scene.import_log.fixups()[0].first, "x.mgf:7");
  EXPECT_EQ(scene.import_log.fixups()[1].kind, "mgf_diffuse_transmission_left_out");
  // Each part's share of what the material scatters, rd + rs + td = 0.55.
  EXPECT_NEAR(scene.import_log.fixups()[0].ShareMean(), 0.1 / 0.55, 1e-15);
  EXPECT_NEAR(scene.import_log.fixups()[1].ShareMean(), 0.2 / 0.55, 1e-15);
  EXPECT_EQ(scene.import_log.Lines()[0],
            "import: 1 MGF material with a specular reflection part (rs) left out of the diffuse "
            "solve: 18% of the light it scatters (rd + rs + td + ts) (first at x.mgf:7)");
  // Same name, same values: the same material; changed values: a second one.
  EXPECT_EQ(ctx.Intern(scene, "x.mgf:8"), index);
  ASSERT_TRUE(ctx.Apply({"rd", "0.5"}).ok());
  EXPECT_EQ(ctx.Intern(scene, "x.mgf:9"), 1u);
  EXPECT_EQ(scene.materials[1].name, "lamp#2");
}

TEST(MgfMaterial, ColourOfEachComponentIsTheOneInForceThen) {
  MgfMaterialContext ctx;
  for (const std::vector<std::string>& w :
       std::vector<std::vector<std::string>>{{"c", "red", "="},
                                             {"cxy", "0.64", "0.33"},
                                             {"m", "x", "="},
                                             {"c", "red"},
                                             {"rd", "0.2"},
                                             {"c"},
                                             {"ed", "358"}}) {
    ASSERT_TRUE(ctx.Apply(w).ok()) << w[0];
  }
  Scene scene;
  const Material& m = scene.materials[ctx.Intern(scene, "")];
  EXPECT_GT(m.reflectance[0], 0.2);
  EXPECT_NEAR(m.reflectance[1], 0, 1e-12);
  EXPECT_NEAR(m.reflectance[2], 0, 1e-12);
  for (int b = 0; b < 3; ++b) EXPECT_NEAR(m.emission[b], 2.0, 1e-12);
  EXPECT_TRUE(m.two_sided);  // the MGF default, sides 2
}

TEST(MgfMaterial, OutOfGamutColourKeepsItsLuminance) {
  // corridor.mgf's "groen": x = 0, y = 0.38, far outside the RGB gamut.
  MgfMaterialContext ctx;
  for (const std::vector<std::string>& w : std::vector<std::vector<std::string>>{
           {"m", "groen", "="}, {"c"}, {"cxy", "0", "0.38"}, {"rd", "0.3"}}) {
    ASSERT_TRUE(ctx.Apply(w).ok()) << w[0];
  }
  Scene scene;
  const Material& m = scene.materials[ctx.Intern(scene, "c.mgf:3")];
  double y = 0;
  const MgfColor c = LinearRgbToXyY(m.reflectance, &y);
  EXPECT_NEAR(y, 0.3, 1e-12);
  EXPECT_NEAR(*std::min_element(m.reflectance.begin(), m.reflectance.end()), 0, 1e-12);
  EXPECT_GT(m.reflectance[1], m.reflectance[0]);  // still green
  EXPECT_LT(c.x, 1.0 / 3);
  ASSERT_EQ(scene.import_log.fixups().size(), 1u);
  EXPECT_EQ(scene.import_log.fixups()[0].kind, "mgf_colour_out_of_gamut");
}

TEST(MgfMaterial, BadValuesAreErrors) {
  MgfMaterialContext ctx;
  EXPECT_FALSE(ctx.Apply({"rd", "1.5"}).ok());
  EXPECT_FALSE(ctx.Apply({"ed", "-1"}).ok());
  EXPECT_FALSE(ctx.Apply({"rs", "0.5"}).ok());
  EXPECT_FALSE(ctx.Apply({"sides", "3"}).ok());
  EXPECT_FALSE(ctx.Apply({"cxy", "0.7", "0.5"}).ok());
  EXPECT_FALSE(ctx.Apply({"c", "nosuch"}).ok());
  EXPECT_FALSE(ctx.Apply({"m", "nosuch"}).ok());
  EXPECT_FALSE(ctx.Apply({"cmix", "1", "nosuch", "1", "nosuch"}).ok());
  EXPECT_FALSE(ctx.Apply({"rd", "abc"}).ok());
}

}  // namespace
}  // namespace radflux
