// Time-lapse ranges: how many frames a range has and which instant each frame shows.
#include <gtest/gtest.h>

#include "engine/scene/scene.h"
#include "engine/scene/scene_io.h"
#include "tests/scene/scene_compare.h"

namespace sky {
namespace {

IsoTime at(const char* text) {
  return IsoTime::parse(text).value();
}

TimeSettings range(const char* start, const char* end, double step) {
  TimeSettings t;
  t.start = at(start);
  t.end = at(end);
  t.stepSeconds = step;
  return t;
}

TEST(TimeSettings, AnInstantIsOneFrame) {
  TimeSettings t;
  t.start = at("2024-06-21T12:00:00+02:00");
  EXPECT_FALSE(t.isRange());
  EXPECT_EQ(t.frameCount(), 1);
  EXPECT_EQ(t.frame(0), t.start);
}

TEST(TimeSettings, WholeNumberOfStepsEndsOnEnd) {
  TimeSettings day = range("2024-06-21T00:00Z", "2024-06-22T00:00Z", 900);
  EXPECT_EQ(day.frameCount(), 97);  // 24 h / 15 min = 96 steps, both ends included
  EXPECT_EQ(day.frame(0), day.start);
  EXPECT_EQ(day.frame(96), *day.end);
  EXPECT_EQ(day.frame(1).format(), "2024-06-21T00:15:00Z");
  EXPECT_EQ(day.frame(48).format(), "2024-06-21T12:00:00Z");
  // Steps that are not exact in binary still land on the end: 1 s / 0.1 s.
  TimeSettings tenths = range("2024-06-21T00:00:00Z", "2024-06-21T00:00:01Z", 0.1);
  EXPECT_EQ(tenths.frameCount(), 11);
  EXPECT_NEAR(tenths.frame(10).secondsSince(*tenths.end), 0.0, 1e-12);
  // 0.3 s / 0.1 s is 2.9999999999999996 in doubles: still three whole steps.
  EXPECT_EQ(range("2024-06-21T00:00:00Z", "2024-06-21T00:00:00.3Z", 0.1).frameCount(), 4);
  TimeSettings thirds = range("2024-06-21T00:00:00Z", "2024-06-21T00:00:01Z", 1.0 / 3.0);
  EXPECT_EQ(thirds.frameCount(), 4);
}

TEST(TimeSettings, PartialLastStepIsDropped) {
  // 1 h / 25 min = 2.4 steps: frames at 0, 25 and 50 min; the end itself is not a frame.
  TimeSettings t = range("2024-06-21T00:00Z", "2024-06-21T01:00Z", 1500);
  EXPECT_EQ(t.frameCount(), 3);
  EXPECT_EQ(t.frame(2).format(), "2024-06-21T00:50:00Z");
  // A step longer than the range leaves the start alone.
  EXPECT_EQ(range("2024-06-21T00:00Z", "2024-06-21T01:00Z", 7200).frameCount(), 1);
  // Just short of a whole number of steps by more than rounding: not counted.
  EXPECT_EQ(range("2024-06-21T00:00Z", "2024-06-21T00:59:59.999Z", 900).frameCount(), 4);
}

TEST(TimeSettings, EndEqualToStartIsOneFrame) {
  TimeSettings t = range("2024-06-21T00:00Z", "2024-06-21T00:00Z", 60);
  EXPECT_TRUE(t.isRange());
  EXPECT_EQ(t.frameCount(), 1);
  EXPECT_EQ(t.frame(0), t.start);
}

TEST(TimeSettings, FramesKeepTheStartZone) {
  // The end may be written in another zone; frames are written in the start's.
  TimeSettings t = range("2024-06-21T22:00:00+05:30", "2024-06-21T22:30:00Z", 3600);
  EXPECT_EQ(t.frameCount(), 7);
  EXPECT_EQ(t.frame(1).format(), "2024-06-21T23:00:00+05:30");
  EXPECT_EQ(t.frame(2).format(), "2024-06-22T00:00:00+05:30");
  EXPECT_EQ(t.frame(6).format(), "2024-06-22T04:00:00+05:30");
  EXPECT_EQ(t.frame(6).secondsSince(*t.end), 0.0);
  EXPECT_NE(t.frame(6), *t.end);  // same instant, other zone
}

TEST(TimeSettings, FramesCrossALeapDay) {
  TimeSettings t = range("2024-02-28T23:00Z", "2024-03-01T01:00Z", 3600);
  EXPECT_EQ(t.frameCount(), 27);
  EXPECT_EQ(t.frame(1).format(), "2024-02-29T00:00:00Z");
  EXPECT_EQ(t.frame(24).format(), "2024-02-29T23:00:00Z");
  EXPECT_EQ(t.frame(25).format(), "2024-03-01T00:00:00Z");
  EXPECT_EQ(t.frame(26), *t.end);
  // The same dates in 2023 have no 29 February between them: two hours, three frames.
  EXPECT_EQ(range("2023-02-28T23:00Z", "2023-03-01T01:00Z", 3600).frameCount(), 3);
}

TEST(TimeSettings, FractionalStepsAndStarts) {
  TimeSettings t = range("2024-06-21T12:00:00.75Z", "2024-06-21T12:00:03Z", 0.5);
  EXPECT_EQ(t.frameCount(), 5);  // 2.25 s / 0.5 s = 4.5 steps
  EXPECT_EQ(t.frame(1).format(), "2024-06-21T12:00:01.25Z");
  EXPECT_EQ(t.frame(4).format(), "2024-06-21T12:00:02.75Z");
  // The frame is computed from the start, not accumulated: no drift over many frames.
  TimeSettings tenths = range("2024-06-21T00:00Z", "2024-06-21T00:16:40Z", 0.1);
  EXPECT_EQ(tenths.frameCount(), 10001);
  EXPECT_EQ(tenths.frame(10000), *tenths.end);
  EXPECT_EQ(tenths.frame(2345).format(), "2024-06-21T00:03:54.5Z");
}

TEST(TimeSettings, ReadFromAFile) {
  Scene s =
      loadSceneText("time: 2024-02-28T23:00Z/2024-03-01T01:00Z/1h\n", ConfigFormat::Yaml, "t.yaml");
  EXPECT_EQ(s.time.frameCount(), 27);
  EXPECT_EQ(s.time.frame(25).format(), "2024-03-01T00:00:00Z");
  // The reader's frame limit is the one frameCount() reports: 100000 frames pass.
  Scene limit = loadSceneText("time: 2024-01-01T00:00Z/2024-01-02T03:46:39Z/1s\n",
                              ConfigFormat::Yaml, "t.yaml");
  EXPECT_EQ(limit.time.frameCount(), TimeSettings::kMaxFrames);
}

}  // namespace
}  // namespace sky
