// FC's converters on their own: HP-GL and DXF text in, part-file text out.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gantry/convert/to_sbp.hpp"
#include "gantry/core/diagnostic.hpp"

namespace gantry {
namespace {

// The lines after the header comments.
std::vector<std::string> body(const std::string& text) {
  std::vector<std::string> out;
  size_t b = 0;
  while (b < text.size()) {
    const size_t e = text.find('\n', b);
    const std::string line = text.substr(b, e - b);
    if (!line.starts_with("'")) out.push_back(line);
    b = e == std::string::npos ? text.size() : e + 1;
  }
  return out;
}

ConvertOptions inches() {
  ConvertOptions o;
  o.source = "drawing";
  o.units = Units::Inches;
  o.cut_z = -0.1;
  o.safe_z = 0.5;
  return o;
}

std::string dxf(const std::vector<std::pair<int, std::string>>& groups) {
  std::string out;
  for (const auto& [code, value] : groups) out += std::to_string(code) + "\n" + value + "\n";
  return out;
}

// An ENTITIES section holding `entities` (groups from each entity's 0).
std::string entities(std::vector<std::pair<int, std::string>> groups) {
  groups.insert(groups.begin(), {{0, "SECTION"}, {2, "ENTITIES"}});
  groups.push_back({0, "ENDSEC"});
  groups.push_back({0, "EOF"});
  return dxf(groups);
}

Diagnostic error_of(auto&& convert) {
  try {
    convert();
  } catch (const GantryError& e) {
    return e.diagnostic();
  }
  ADD_FAILURE() << "no error";
  return {};
}

// ---- HP-GL -------------------------------------------------------------------------------

TEST(HpglToSbp, PenDownMovesBecomeCutsAtCutZWithJogsBetween) {
  const Conversion c = hpgl_to_sbp("IN;PU0,0;PD1016,0,1016,1016;PU2032,0;PD2032,1016;", inches());
  EXPECT_EQ(c.paths, 2u);
  EXPECT_EQ(body(c.text), (std::vector<std::string>{"SA", "JZ, 0.5", "J2, 0, 0", "MZ, -0.1",
                                                    "M2, 1, 0", "M2, 1, 1", "JZ, 0.5", "J2, 2, 0",
                                                    "MZ, -0.1", "M2, 2, 1", "JZ, 0.5"}));
  EXPECT_TRUE(c.notes.empty());
  EXPECT_NE(c.text.find("' Part file converted by Gantry FC from drawing (HP-GL)\n"),
            std::string::npos);
}

TEST(HpglToSbp, RelativeAbsoluteAndPenSelection) {
  // PR: points from the last; SP0 puts the pen away (up); PA returns to absolute points.
  const Conversion c = hpgl_to_sbp(
      "IN;SP1;PU1016,0;PR;PD1016,0,0,1016;SP0;PD-1016,0;PA;SP1;"
      "PD0,0;",
      inches());
  EXPECT_EQ(body(c.text), (std::vector<std::string>{"SA", "JZ, 0.5", "J2, 1, 0", "MZ, -0.1",
                                                    "M2, 2, 0", "M2, 2, 1", "JZ, 0.5", "J2, 1, 1",
                                                    "MZ, -0.1", "M2, 0, 0", "JZ, 0.5"}));
}

TEST(HpglToSbp, SeparatorsMayBeSpacesAndInstructionsNeedNoSemicolon) {
  const Conversion c = hpgl_to_sbp("IN PU 0 0 PD 1016 0\n", inches());
  EXPECT_EQ(body(c.text), (std::vector<std::string>{"SA", "JZ, 0.5", "J2, 0, 0", "MZ, -0.1",
                                                    "M2, 1, 0", "JZ, 0.5"}));
}

TEST(HpglToSbp, PlotterUnitsAreAFortiethOfAMillimetreUnlessScaled) {
  ConvertOptions o = inches();
  o.units = Units::Millimetres;
  EXPECT_NE(hpgl_to_sbp("PU0,0;PD40,80;", o).text.find("\nM2, 1, 2\n"), std::string::npos);
  o.scale = 0.5;  // part-file units per plotter unit
  EXPECT_NE(hpgl_to_sbp("PU0,0;PD40,80;", o).text.find("\nM2, 20, 40\n"), std::string::npos);
}

TEST(HpglToSbp, InstructionsThatDrawOtherwiseAreNamed) {
  const Conversion c =
      hpgl_to_sbp("IN;VS10;LT;PU0,0;PD1016,0;CI50;AA0,0,90;LBhello\x03;", inches());
  EXPECT_EQ(c.notes, (std::vector<std::string>{"1 AA instruction(s)", "1 CI instruction(s)",
                                               "1 LB instruction(s) (labels)"}));
  EXPECT_NE(c.text.find("' Not converted: 1 CI instruction(s)\n"), std::string::npos);
  EXPECT_EQ(c.paths, 1u);
}

TEST(HpglToSbp, ErrorsAreLocatedInThePlot) {
  Diagnostic d = error_of([] { hpgl_to_sbp("IN;\nPD1,2,3;\n", inches()); });
  EXPECT_EQ(format(d),
            "drawing:2:1: error: FC: PD has 3 numbers; its points need an X and a Y "
            "each");
  d = error_of([] { hpgl_to_sbp("IN;PU0,0;\n  7;", inches()); });
  EXPECT_EQ(d.loc.line, 2);
  EXPECT_EQ(d.loc.column, 3);
  EXPECT_NE(d.message.find("expected an HP-GL instruction"), std::string::npos);
}

// ---- DXF -----------------------------------------------------------------------------------

TEST(DxfToSbp, LinesThatMeetAreCutWithoutLifting) {
  const Conversion c = dxf_to_sbp(entities({{0, "LINE"},
                                            {10, "0"},
                                            {20, "0"},
                                            {11, "2"},
                                            {21, "0"},
                                            {0, "LINE"},
                                            {10, "2"},
                                            {20, "0"},
                                            {11, "2"},
                                            {21, "1"},
                                            {0, "LINE"},
                                            {10, "5"},
                                            {20, "5"},
                                            {11, "6"},
                                            {21, "5"}}),
                                  inches());
  EXPECT_EQ(c.paths, 2u);
  EXPECT_EQ(body(c.text), (std::vector<std::string>{"SA", "JZ, 0.5", "J2, 0, 0", "MZ, -0.1",
                                                    "M2, 2, 0", "M2, 2, 1", "JZ, 0.5", "J2, 5, 5",
                                                    "MZ, -0.1", "M2, 6, 5", "JZ, 0.5"}));
}

TEST(DxfToSbp, ArcsAndCirclesBecomeCgWithCentreOffsetsFromTheStart) {
  const Conversion c = dxf_to_sbp(entities({{0, "ARC"},
                                            {10, "6"},
                                            {20, "1"},
                                            {40, "1"},
                                            {50, "0"},
                                            {51, "90"},
                                            {0, "CIRCLE"},
                                            {10, "9"},
                                            {20, "2"},
                                            {40, "0.5"}}),
                                  inches());
  EXPECT_EQ(body(c.text), (std::vector<std::string>{
                              "SA", "JZ, 0.5", "J2, 7, 1", "MZ, -0.1",
                              "CG, , 6, 2, -1, 0, T, -1, , , , , , 1", "JZ, 0.5", "J2, 9.5, 2",
                              "MZ, -0.1", "CG, , 9.5, 2, -0.5, 0, T, -1, , , , , , 1", "JZ, 0.5"}));
}

TEST(DxfToSbp, PolylineBulgesAreArcsEitherWay) {
  // LWPOLYLINE, closed: a half circle clockwise over the top (bulge -1), then straight back.
  Conversion c = dxf_to_sbp(entities({{0, "LWPOLYLINE"},
                                      {90, "2"},
                                      {70, "1"},
                                      {10, "10"},
                                      {20, "0"},
                                      {42, "-1"},
                                      {10, "12"},
                                      {20, "0"}}),
                            inches());
  EXPECT_EQ(body(c.text), (std::vector<std::string>{"SA", "JZ, 0.5", "J2, 10, 0", "MZ, -0.1",
                                                    "CG, , 12, 0, 1, 0, T, 1, , , , , , 1",
                                                    "M2, 10, 0", "JZ, 0.5"}));
  // POLYLINE with VERTEX entities: a quarter circle counter-clockwise (bulge tan 22.5 deg).
  c = dxf_to_sbp(entities({{0, "POLYLINE"},
                           {66, "1"},
                           {70, "0"},
                           {0, "VERTEX"},
                           {10, "15"},
                           {20, "0"},
                           {42, "0.41421356237"},
                           {0, "VERTEX"},
                           {10, "16"},
                           {20, "1"},
                           {0, "SEQEND"}}),
                 inches());
  EXPECT_EQ(body(c.text),
            (std::vector<std::string>{"SA", "JZ, 0.5", "J2, 15, 0", "MZ, -0.1",
                                      "CG, , 16, 1, 0, 1, T, -1, , , , , , 1", "JZ, 0.5"}));
}

TEST(DxfToSbp, AMirroredArcRunsTheOtherWay) {
  // Extrusion (0, 0, -1): the object's X is the drawing's -X.
  const Conversion c = dxf_to_sbp(entities({{0, "ARC"},
                                            {10, "-6"},
                                            {20, "1"},
                                            {40, "1"},
                                            {50, "0"},
                                            {51, "90"},
                                            {210, "0"},
                                            {220, "0"},
                                            {230, "-1"}}),
                                  inches());
  // The object's centre (-6, 1) is the drawing's (6, 1); its 0 to 90 degrees run clockwise
  // from (5, 1) to (6, 2).
  EXPECT_NE(c.text.find("J2, 5, 1\nMZ, -0.1\nCG, , 6, 2, 1, 0, T, 1, , , , , , 1\n"),
            std::string::npos)
      << c.text;
}

TEST(DxfToSbp, InsunitsScaleTheDrawingToThePartFilesUnits) {
  std::string text =
      dxf({{0, "SECTION"}, {2, "HEADER"}, {9, "$INSUNITS"}, {70, "4"}, {0, "ENDSEC"}}) +
      entities({{0, "LINE"}, {10, "0"}, {20, "0"}, {11, "50.8"}, {21, "25.4"}});
  EXPECT_NE(dxf_to_sbp(text, inches()).text.find("\nM2, 2, 1\n"), std::string::npos);
  ConvertOptions mm = inches();
  mm.units = Units::Millimetres;
  EXPECT_NE(dxf_to_sbp(text, mm).text.find("\nM2, 50.8, 25.4\n"), std::string::npos);
  mm.scale = 2;  // given: it wins over the drawing's units
  EXPECT_NE(dxf_to_sbp(text, mm).text.find("\nM2, 101.6, 50.8\n"), std::string::npos);
}

TEST(DxfToSbp, OtherEntitiesAreNamedAndBlocksAreNotCut) {
  const std::string text =
      dxf({{0, "SECTION"},
           {2, "BLOCKS"},
           {0, "BLOCK"},
           {0, "LINE"},
           {10, "0"},
           {20, "0"},
           {11, "9"},
           {21, "9"},
           {0, "ENDBLK"},
           {0, "ENDSEC"}}) +
      entities({{0, "TEXT"}, {1, "hi"}, {0, "SPLINE"}, {0, "TEXT"}, {1, "again"}, {0, "INSERT"}});
  const Conversion c = dxf_to_sbp(text, inches());
  EXPECT_EQ(c.paths, 0u);
  EXPECT_EQ(c.notes, (std::vector<std::string>{"1 INSERT entity(ies)", "1 SPLINE entity(ies)",
                                               "2 TEXT entity(ies)"}));
  EXPECT_EQ(body(c.text), (std::vector<std::string>{"SA", "JZ, 0.5"}));
}

TEST(DxfToSbp, ErrorsAreLocatedInTheDrawing) {
  Diagnostic d = error_of([] { dxf_to_sbp("0\nSECTION\n2\nENTITIES\nten\nLINE\n", inches()); });
  EXPECT_EQ(format(d),
            "drawing:5: error: FC: expected a DXF group code (a whole number) on this "
            "line, found 'ten'");
  d = error_of([] {
    dxf_to_sbp(entities({{0, "LINE"}, {10, "1,5"}, {20, "0"}, {11, "2"}, {21, "0"}}), inches());
  });
  EXPECT_EQ(d.loc.line, 8);  // the value line of group 10
  EXPECT_NE(d.message.find("group 10 should hold a number, not '1,5'"), std::string::npos);
  d = error_of([] { dxf_to_sbp(entities({{0, "CIRCLE"}, {10, "1"}, {20, "1"}}), inches()); });
  EXPECT_NE(d.message.find("this CIRCLE has no group 40"), std::string::npos);
  d = error_of([] { dxf_to_sbp("AutoCAD Binary DXF\r\n\x1a", inches()); });
  EXPECT_NE(d.message.find("binary DXF"), std::string::npos);
}

}  // namespace
}  // namespace gantry
