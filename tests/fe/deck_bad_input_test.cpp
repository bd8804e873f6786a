// Bad decks (issue 5 item 4): truncated files, binary garbage, NaN/Inf, huge counts,
// duplicate labels, undefined sets, missing data lines, unknown keywords. Each must be a
// DeckError naming the line and the reason — never a crash, a hang, or a silent default.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "fe/deck/deck_reader.hpp"

namespace fd = ringcrush::fe::deck;

namespace {

// Reads `text` and expects a DeckError at `line` whose reason contains `fragment`.
void expect_error(const std::string& text, int line, const std::string& fragment) {
  try {
    fd::read_deck(text);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const fd::DeckError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(e.reason().find(fragment), std::string::npos) << "reason: " << e.reason();
  }
}

std::string static_deck() {
  std::ifstream in(std::string(RINGCRUSH_SOURCE_DIR) + "/data/thesis/thesis_static.inp");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first `lines` lines of the static deck, the last one cut after `keep` characters.
std::string truncated(int lines, std::size_t keep) {
  std::istringstream in(static_deck());
  std::string out, l;
  for (int i = 1; i <= lines && std::getline(in, l); ++i) out += (i < lines ? l + "\n" : l.substr(0, keep));
  return out;
}

const std::string two_nodes = "*NODE\n1,0.,0.\n2,1.,0.\n";

}  // namespace

TEST(DeckTruncated, StepWithoutEndStep) {
  expect_error(truncated(137, 100), 101, "no *END STEP");
}

TEST(DeckTruncated, InsideAnElementLine) {
  expect_error(truncated(19, 11), 19, "element 101 has 2 nodes, CPS8 needs 8");
}

TEST(DeckTruncated, InsideAContinuedKeywordLine) {
  expect_error(truncated(28, 25), 28, "truncated");
}

TEST(DeckTruncated, EmptyFileAndCommentsOnly) {
  expect_error("", 0, "no keyword lines");
  expect_error("** only a comment\n\n", 0, "no keyword lines");
}

TEST(DeckGarbage, ControlBytes) {
  expect_error(std::string("*NODE\n1,0.,0.\n\x01\x02\x00\xff", 18), 3, "control character");
}

TEST(DeckGarbage, NonAsciiOutsideCommentsAndHeading) {
  expect_error("*HEADING\nANEL \xc3\xa9 OK\n*NODE\n1,0.\xc3\xa9,0.\n", 4, "non-ASCII");
  EXPECT_NO_THROW(fd::read_deck("** coment\xc3\xa1rio\n*HEADING\nAN\xc3\x89L\n*NODE\n1,0.,0.\n"));
}

TEST(DeckGarbage, DataBeforeAnyKeyword) { expect_error("1,2,3\n*NODE\n1,0,0\n", 1, "before the first keyword"); }

TEST(DeckNumbers, NanAndInfAreRefused) {
  expect_error("*NODE\n1,nan,0.\n", 2, "'nan' is not a finite number");
  expect_error("*NODE\n1,0.,INF\n", 2, "is not a finite number");
  expect_error("*NODE\n1,1.E999,0.\n", 2, "is not a finite number");
  expect_error(two_nodes + "*NSET,NSET=A\n1,2\n*STEP\n*STATIC,PTOL=NAN\n1.,1.\n*END STEP\n", 7, "PTOL=NAN");
  expect_error("*NODE\n1,0.x,0.\n", 2, "'0.x' is not a finite number");
}

TEST(DeckCounts, HugeLabelsAndGenerationsAreRefusedBeforeAllocating) {
  expect_error("*NODE\n1000000000000,0.,0.\n", 2, "1000000000000 outside 1..99999999");
  expect_error("*NODE\n100000000000000000000000,0.,0.\n", 2, "is not an integer");  // beyond 64 bits
  expect_error("*NODE\n100000000,0.,0.\n", 2, "outside 1..99999999");
  expect_error("*NODE\n1,0.,0.\n99999999,1.,0.\n*NGEN\n1,99999999,1\n", 5, "number of generated intervals");
  expect_error(two_nodes + "*ELEMENT,TYPE=MASS\n1,1\n*ELGEN\n1,3000000,0,1\n", 7, "number of elements 3000000");
  expect_error(two_nodes + "*ELEMENT,TYPE=MASS\n1,1\n*ELGEN\n1,1000,0,1,1001,0,1000\n", 7, "number of generated elements 1001000");
  expect_error(two_nodes + "*NSET,NSET=A,GENERATE\n1,99999999,1\n", 5, "number of generated members");
  expect_error(two_nodes + "*STEP,INC=1000000000000\n", 4, "INC=1000000000000");
}

TEST(DeckDuplicates, NodeElementMaterialAndParameter) {
  expect_error("*NODE\n1,0.,0.\n1,1.,0.\n", 3, "node 1 defined twice (first at line 2)");
  expect_error(two_nodes + "*ELEMENT,TYPE=MASS\n7,1\n7,2\n", 6, "element 7 defined twice");
  expect_error("*MATERIAL,NAME=STEEL\n*MATERIAL,NAME=steel\n", 2, "STEEL defined twice");
  expect_error("*NODE,NSET=A,nset=B\n1,0.,0.\n", 1, "NSET given twice");
  // A generated node that exists already is a duplicate too, not a silent redefinition.
  expect_error("*NODE\n1,0.,0.\n2,0.5,0.\n3,1.,0.\n*NGEN\n1,3,1\n", 6, "node 2 defined twice");
}

TEST(DeckUndefined, SetsNodesAndMaterials) {
  expect_error(two_nodes + "*BOUNDARY\nNOPE,1\n", 5, "node set NOPE is not defined");
  expect_error(two_nodes + "*ELSET,ELSET=ALL\nRING1\n", 5, "element set RING1 is not defined");
  expect_error(two_nodes + "*NCOPY,CHANGE NUMBER=10,OLD SET=A1,SHIFT\n0.,1.,0.\n", 4, "node set A1 is not defined");
  expect_error(two_nodes + "*ELEMENT,TYPE=MASS\n1,3\n", 5, "node 3, which is not defined");
  expect_error("*NODE\n1,0.,0.\n*NGEN\n1,5,1\n", 4, "end node 5 is not defined");
  const std::string quad = "*NODE\n1,0.,0.\n2,1.,0.\n3,1.,1.\n4,0.,1.\n5,.5,0.\n6,1.,.5\n7,.5,1.\n8,0.,.5\n"
                           "*ELEMENT,TYPE=CPS8,ELSET=E\n1,1,2,3,4,5,6,7,8\n";
  expect_error(quad + "*SOLID SECTION,ELSET=E,MATERIAL=STEEL\n1.\n", 12, "material STEEL is never defined");
  expect_error("*ELASTIC\n2.E11,.3\n", 1, "must follow *MATERIAL");
}

TEST(DeckMissing, DataLinesAndParameters) {
  expect_error("*NODE\n*ELEMENT,TYPE=CPS8\n", 1, "*NODE: missing data line");
  expect_error("*MATERIAL,NAME=S\n*ELASTIC\n*PLASTIC\n2.E8,0.\n", 2, "*ELASTIC: missing data line");
  expect_error("*ELEMENT\n1,1\n", 1, "required parameter TYPE is missing");
}

TEST(DeckKeywords, UnknownKeywordsParametersAndPlacement) {
  expect_error(two_nodes + "*BEAM SECTION,ELSET=A\n", 4, "unknown or unsupported keyword *BEAM SECTION");
  expect_error("*NODE,NSETT=A\n1,0.,0.\n", 1, "unknown parameter NSETT");
  expect_error(two_nodes + "*STEP\n*NODE\n3,0.,0.\n", 5, "model data and cannot appear inside a step");
  expect_error(two_nodes + "*STATIC\n1.,1.\n", 4, "only valid inside a *STEP");
  expect_error(two_nodes + "*STEP\n*END STEP\n", 5, "has no procedure");
  expect_error(two_nodes + "*BOUNDARY\n1,XYMM\n", 5, "unknown boundary type 'XYMM'");
  expect_error(two_nodes + "*DISPLACED\nU\n", 4, "must follow *PLOT");
}

TEST(DeckValues, NonPhysicalMaterialAndSteps) {
  expect_error("*MATERIAL,NAME=S\n*ELASTIC\n-2.E11,.3\n", 3, "Young's modulus must be positive");
  expect_error("*MATERIAL,NAME=S\n*ELASTIC\n2.E11,.5\n", 3, "Poisson's ratio 0.5 outside");
  expect_error("*MATERIAL,NAME=S\n*PLASTIC\n2.7E8,0.\n3.2E8,0.\n", 4, "plastic strains must increase");
  expect_error("*MATERIAL,NAME=S\n*PLASTIC\n2.7E8,0.1\n", 3, "must be at plastic strain 0");
  expect_error(two_nodes + "*STEP\n*DYNAMIC,ALPHA=-0.5\n1.E-6,1.E-3\n*END STEP\n", 5, "ALPHA");
  expect_error(two_nodes + "*STEP\n*STATIC\n0.,1.\n*END STEP\n", 6, "initial increment must be positive");
}

TEST(DeckCounts, IncrementsThatWouldOverflowLabelArithmeticAreRefused) {
  expect_error(two_nodes + "*ELEMENT,TYPE=MASS\n1,1\n*ELGEN\n1,2,9000000000000000000,1\n", 7, "node increment");
  expect_error(two_nodes + "*NSET,NSET=A\n1\n*NCOPY,CHANGE NUMBER=9000000000000000000,OLD SET=A,SHIFT\n0.,0.\n", 6,
               "CHANGE NUMBER");
}

TEST(DeckCounts, AmplificationBySetReferencesHitsTheGenerationBudget) {
  // 10^6 nodes from two *NODE lines and one *NGEN, then the set of them referenced over and
  // over: each line is small, the total is refused at the keyword that crosses max_generated.
  std::string deck = "*NODE\n1,0.,0.\n1000000,1.,0.\n*NGEN,NSET=BIG\n1,1000000,1\n*NSET,NSET=COPY\n";
  for (int i = 0; i < 5; ++i) deck += "BIG\n";
  try {
    fd::read_deck(deck);
    ADD_FAILURE() << "accepted";
  } catch (const fd::DeckError& e) {
    EXPECT_EQ(e.line(), 6);
    EXPECT_NE(e.reason().find("generates more than"), std::string::npos) << e.what();
  }
}

TEST(DeckKeywordsLimits, TooManyParameters) {
  std::string line = "*NODE";
  for (int i = 0; i < 70; ++i) line += ",P" + std::to_string(i) + "=1";
  expect_error(line + "\n1,0.,0.\n", 1, "more than 64 parameters");
}
