#include "engine/scene/config_tree.h"

#include <gtest/gtest.h>

#include "tests/scene/scene_test_util.h"

namespace sky {
namespace {

using test::errorOf;

std::string at(const SourcePos& p) {
  return p.str();
}

TEST(ConfigTree, YamlKeepsPositionsAndStyles) {
  ConfigNode root = parseYamlTree(
      "output:\n  width: 64\n  name: \"64\"\nsky:\n  sky_color: [0.1, 0.2, 0.3]\n", "a.yaml");
  ASSERT_TRUE(root.isMap());
  ASSERT_EQ(root.children.size(), 2u);
  const ConfigNode* width = root.find("output")->find("width");
  ASSERT_NE(width, nullptr);
  EXPECT_EQ(width->style, ConfigNode::Style::Plain);
  EXPECT_EQ(width->text, "64");
  EXPECT_EQ(at(width->keyPos), "a.yaml:2:3");
  EXPECT_EQ(at(width->pos), "a.yaml:2:10");
  const ConfigNode* name = root.find("output")->find("name");
  EXPECT_EQ(name->style, ConfigNode::Style::String);
  const ConfigNode* color = root.find("sky")->find("sky_color");
  ASSERT_EQ(color->kind, ConfigNode::Kind::Sequence);
  ASSERT_EQ(color->children.size(), 3u);
  EXPECT_EQ(at(color->children[2].pos), "a.yaml:5:25");
  EXPECT_EQ(root.find("nope"), nullptr);
}

TEST(ConfigTree, JsonKeepsPositionsAndStyles) {
  const char* text =
      "{\n"
      "  \"output\": {\"width\": 64, \"name\": \"sky\", \"exposure_ev\": -1.50},\n"
      "  \"sky\": {\n"
      "    \"sky_color\": [0.1,  2e-1 , 3],\n"
      "    \"flag\": true, \"none\": null\n"
      "  }\n"
      "}\n";
  ConfigNode root = parseJsonTree(text, "a.json");
  const ConfigNode* output = root.find("output");
  ASSERT_NE(output, nullptr);
  EXPECT_EQ(at(output->keyPos), "a.json:2:3");
  const ConfigNode* width = output->find("width");
  EXPECT_EQ(width->style, ConfigNode::Style::Number);
  EXPECT_EQ(width->text, "64");
  // Values of map members report their key's position.
  EXPECT_EQ(at(width->keyPos), "a.json:2:14");
  EXPECT_EQ(at(width->pos), "a.json:2:14");
  EXPECT_EQ(at(output->find("name")->keyPos), "a.json:2:27");
  EXPECT_EQ(output->find("name")->style, ConfigNode::Style::String);
  EXPECT_EQ(output->find("exposure_ev")->text, "-1.50");  // the digits as written
  EXPECT_EQ(at(output->find("exposure_ev")->keyPos), "a.json:2:42");
  const ConfigNode* color = root.find("sky")->find("sky_color");
  ASSERT_EQ(color->children.size(), 3u);
  EXPECT_EQ(at(color->pos), "a.json:4:5");
  // List items keep their own positions.
  EXPECT_EQ(at(color->children[0].pos), "a.json:4:19");
  EXPECT_EQ(at(color->children[1].pos), "a.json:4:25");
  EXPECT_EQ(color->children[1].text, "2e-1");
  EXPECT_EQ(at(color->children[2].pos), "a.json:4:32");
  EXPECT_EQ(root.find("sky")->find("flag")->style, ConfigNode::Style::Bool);
  EXPECT_EQ(at(root.find("sky")->find("none")->keyPos), "a.json:5:19");
  EXPECT_EQ(root.find("sky")->find("none")->kind, ConfigNode::Kind::Null);
}

TEST(ConfigTree, JsonNumbersKeepTheirText) {
  ConfigNode root = parseJsonTree(
      "{\"a\": -0, \"b\": 18446744073709551615, \"c\": 1E+2, \"d\": [-12,3]}", "n.json");
  EXPECT_EQ(root.find("a")->text, "-0");
  EXPECT_EQ(root.find("b")->text, "18446744073709551615");
  EXPECT_EQ(root.find("c")->text, "1E+2");
  EXPECT_EQ(root.find("d")->children[0].text, "-12");
  EXPECT_EQ(root.find("d")->children[1].text, "3");
}

TEST(ConfigTree, JsonColumnsCountCharactersNotBytes) {
  ConfigNode root = parseJsonTree("{\"name\": \"\xc3\xa9t\xc3\xa9\", \"x\": 1}", "u.json");
  EXPECT_EQ(at(root.find("x")->keyPos), "u.json:1:17");
}

TEST(ConfigTree, EmptyYamlIsAnEmptyMap) {
  EXPECT_TRUE(parseYamlTree("", "e.yaml").isMap());
  EXPECT_TRUE(parseYamlTree("# only a comment\n", "e.yaml").children.empty());
}

TEST(ConfigTree, DuplicateKeys) {
  EXPECT_EQ(
      errorOf([] { parseYamlTree("camera:\n  pitch: 1\n  heading: 2\n  pitch: 3\n", "d.yaml"); }),
      "d.yaml:4:3: camera.pitch: duplicate key (first given at line 2)");
  EXPECT_EQ(errorOf([] { parseYamlTree("time: 1\nsky: {}\ntime: 2\n", "d.yaml"); }),
            "d.yaml:3:1: time: duplicate key (first given at line 1)");
  EXPECT_EQ(
      errorOf([] { parseJsonTree("{\"camera\": {\n  \"pitch\": 1,\n  \"pitch\": 2}}", "d.json"); }),
      "d.json:3:3: camera.pitch: duplicate key (first given at line 2)");
}

TEST(ConfigTree, SyntaxErrors) {
  EXPECT_EQ(errorOf([] { parseYamlTree("output:\n  width: [64\n", "s.yaml"); }),
            "s.yaml:3:1: YAML syntax error: end of sequence flow not found");
  std::string json = errorOf([] { parseJsonTree("{\n  \"width\": 64,\n}\n", "s.json"); });
  EXPECT_EQ(json.rfind("s.json:3:1: JSON syntax error: ", 0), 0u) << json;
  std::string nan = errorOf([] { parseJsonTree("{\"camera\": {\n  \"pitch\": NaN}}", "n.json"); });
  EXPECT_EQ(nan.rfind("n.json:2:12: JSON syntax error: ", 0), 0u) << nan;
  EXPECT_NE(nan.find("(in camera.pitch)"), std::string::npos) << nan;
  EXPECT_EQ(errorOf([] { parseJsonTree("{\"camera\": {\n  \"pitch\": -1e999}}", "o.json"); }),
            "o.json:2:3: camera.pitch: -1e999 is out of range (not a finite number)");
  // {"sky": {"c": [1, 1e999]}}: the number starts at column 19.
  EXPECT_EQ(errorOf([] { parseJsonTree("{\"sky\": {\"c\": [1, 1e999]}}", "o.json"); }),
            "o.json:1:19: sky.c: 1e999 is out of range (not a finite number)");
  EXPECT_EQ(errorOf([] { parseJsonTree(" 1e999", "o.json"); }),
            "o.json:1:2: 1e999 is out of range (not a finite number)");
  std::string empty = errorOf([] { parseJsonTree("", "empty.json"); });
  EXPECT_EQ(empty.rfind("empty.json:1:1: JSON syntax error: ", 0), 0u) << empty;
  std::string trailing = errorOf([] { parseJsonTree("{} {}", "t.json"); });
  EXPECT_EQ(trailing.rfind("t.json:1:4: JSON syntax error: ", 0), 0u) << trailing;
}

TEST(ConfigTree, YamlStrayTokensAreErrors) {
  // yaml-cpp 0.7's YAML::Load returns an empty document for these and LoadAll never ends.
  EXPECT_EQ(errorOf([] { parseYamlTree(", x\n", "s.yaml"); }),
            "s.yaml:1:1: YAML syntax error: unexpected text");
  EXPECT_EQ(errorOf([] { parseYamlTree("# comment\n, looking south\nsun: {}\n", "s.yaml"); }),
            "s.yaml:2:1: YAML syntax error: unexpected text");
  // A syntax error wins over a problem found in the events before it.
  EXPECT_EQ(errorOf([] {
              parseYamlTree("a: 1\na: 2\nb: [\n", "s.yaml");
            }).rfind("s.yaml:4:1: YAML syntax error: ", 0),
            0u);
}

TEST(ConfigTree, TopLevelMustBeAMap) {
  EXPECT_EQ(errorOf([] { parseYamlTree("- 1\n- 2\n", "l.yaml"); }),
            "l.yaml:1:1: expected a map of sections at the top level, got a list");
  EXPECT_EQ(errorOf([] { parseJsonTree("  [1]", "l.json"); }),
            "l.json:1:3: expected an object of sections at the top level, got a list");
  EXPECT_EQ(errorOf([] { parseYamlTree("a: 1\n---\nb: 2\n", "m.yaml"); }),
            "m.yaml:2:1: more than one YAML document (one scene per file)");
}

TEST(ConfigTree, YamlTagsAndKeys) {
  EXPECT_EQ(parseYamlTree("a: !!str 64\n", "t.yaml").find("a")->style, ConfigNode::Style::String);
  EXPECT_EQ(errorOf([] { parseYamlTree("a: !!float 1\n", "t.yaml"); }),
            "t.yaml:1:4: a: unsupported YAML tag 'tag:yaml.org,2002:float'");
  EXPECT_EQ(errorOf([] { parseYamlTree("? [1, 2]\n: 3\n", "k.yaml"); }),
            "k.yaml:1:3: map keys must be plain names");
  // Anchors and aliases resolve to copies.
  ConfigNode aliased = parseYamlTree("a: &c [1, 2, 3]\nb: *c\n", "t.yaml");
  EXPECT_EQ(aliased.find("b")->children.size(), 3u);
}

TEST(ConfigTree, OverrideValuesAreYaml) {
  SourcePos pos{"--set x=1", 0, 0};
  EXPECT_EQ(pos.str(), "--set x=1");
  ConfigNode list = parseYamlValue("[0.1,0.2,0.3]", pos);
  ASSERT_EQ(list.kind, ConfigNode::Kind::Sequence);
  EXPECT_EQ(list.children[1].text, "0.2");
  EXPECT_EQ(at(list.children[1].pos), "--set x=1");
  EXPECT_EQ(parseYamlValue("'64'", pos).style, ConfigNode::Style::String);
  EXPECT_EQ(parseYamlValue("", pos).kind, ConfigNode::Kind::Null);
  EXPECT_EQ(parseYamlValue("2024-01-01T00:00:00Z", pos).text, "2024-01-01T00:00:00Z");
  EXPECT_EQ(errorOf([&] { parseYamlValue("[1,", pos); }).rfind("--set x=1: YAML syntax error: ", 0),
            0u);
}

}  // namespace
}  // namespace sky

namespace sky {
namespace {

TEST(ConfigTree, MessageTextStaysOnOneLine) {
  EXPECT_EQ(messageText("a\nb\tc\x01"), "a\\nb\\tc\\x01");
  EXPECT_EQ(messageText(std::string(70, 'x')), std::string(60, 'x') + "...");
  EXPECT_EQ(messageText("\xc3\xa9\xc3\xa9", 3),
            "\xc3\xa9\xc3\xa9");  // never cut inside a character
  EXPECT_EQ(messageText("\xc3\xa9\xc3\xa9\xc3\xa9", 4), "\xc3\xa9\xc3\xa9...");
}

}  // namespace
}  // namespace sky
