// rib_conditional_test.cpp: conditional RIB (IfBegin "expr" / ElseIf / Else / IfEnd):
// which branch a target sees, the expression language (conditional.h) over Option and
// Attribute values and $Frame, nesting (a branch not taken is not evaluated), attribute
// scoping of the values, and the errors: misplaced ElseIf/Else/IfEnd, an IfBegin never
// closed, a bad expression, hostile expressions that must neither crash nor hang.
#include <gtest/gtest.h>

#include <chrono>

#include "rib/conditional.h"
#include "rib_corpus.h"

namespace {

using Lines = std::vector<std::string>;

// The sphere radii a target sees.
Lines spheres(const ribtest::ReadResult& r) {
    Lines out;
    for (const std::string& c : r.target.calls)
        if (c.rfind("sphere ", 0) == 0) out.push_back(c.substr(7, c.find(' ', 7) - 7));
    return out;
}

bool eval(const std::string& expr, std::string* error = nullptr) {
    bool result = false;
    std::string why;
    const bool ok = rib::evaluateCondition(
        expr,
        [](const std::string& name) -> std::optional<rib::CondValue> {
            const std::string n =
                name.find(':') == std::string::npos ? "user:" + name : name;
            rib::CondValue v;
            if (n == "user:name")
                v.text = "hero_body";
            else if (n == "user:n")
                v.isNumber = true, v.number = 3;
            else if (n == "user:empty")
                v.text = "";
            else
                return std::nullopt;
            return v;
        },
        result, why);
    if (error) *error = ok ? "" : why;
    return ok && result;
}

}  // namespace

TEST(RibConditional, ExpressionLanguage) {
    EXPECT_TRUE(eval("$user:name == 'hero_body'"));
    EXPECT_TRUE(eval("${name} != 'villain'"));         // the group defaults to user
    EXPECT_TRUE(eval("$n > 2 && $n <= 3"));            // numbers as numbers
    EXPECT_FALSE(eval("$n < 10 && '10' < '9' == 0"));  // strings as strings: '10' < '9'
    EXPECT_TRUE(eval("$name =~ '^hero_' || 0"));
    EXPECT_TRUE(eval("!($n == 4) && !!1"));
    EXPECT_TRUE(eval("defined($name) && !defined(missing) && $missing == ''"));
    EXPECT_TRUE(eval("concat($name, '-', $n) == 'hero_body-3'"));
    EXPECT_TRUE(eval("match('b.dy$', $name)"));
    EXPECT_FALSE(eval("$empty"));
    EXPECT_TRUE(eval("2.5 == 2.50 && -1 < 0"));
    std::string why;
    EXPECT_FALSE(eval("$n ==", &why));
    EXPECT_EQ(why, "a value expected at column 6");
    EXPECT_FALSE(eval("($n", &why));
    EXPECT_EQ(why, "')' expected at column 4");
    EXPECT_FALSE(eval("$name =~ '('", &why));
    EXPECT_NE(why.find("bad regular expression"), std::string::npos) << why;
    EXPECT_FALSE(eval("frob(1)", &why));
    EXPECT_EQ(why, "unknown function frob() at column 8");
}

// Deep nesting, a long run of '!', a pathological regular expression: an error or an
// answer, quickly, and no crash.
TEST(RibConditional, HostileExpressionsNeitherCrashNorHang) {
    const auto t0 = std::chrono::steady_clock::now();
    std::string why;
    EXPECT_FALSE(eval(std::string(100000, '(') + "1" + std::string(100000, ')'), &why));
    EXPECT_NE(why.find("nested too deeply"), std::string::npos);
    EXPECT_TRUE(eval(std::string(100000, '!') + "1"));  // an even number of them
    EXPECT_FALSE(eval("concat('" + std::string(300, 'a') + "') =~ '(a*)*b'", &why));
    EXPECT_NE(why.find("longer than 256"), std::string::npos) << why;
    EXPECT_FALSE(eval("'" + std::string(30, 'a') + "' =~ '^(a|aa)*$' && 0"));
    // patterns that backtrack exponentially in std::regex (as the reader used): RE2
    // matches in time linear in the subject
    EXPECT_FALSE(eval("'" + std::string(250, 'a') + "' =~ '(a*)*b'"));
    EXPECT_TRUE(eval("'" + std::string(250, 'a') + "' =~ '^(a|aa)*$'"));
    EXPECT_FALSE(eval("'" + std::string(40, 'a') + "!' =~ '^(a+)+$'"));
    // a back-reference is an error; a backslash and 19 digits (found by fuzzing:
    // std::regex overflowed a signed integer reading them as one) an octal escape and
    // digits, which 'a' does not match
    EXPECT_FALSE(eval("'aa' =~ '(a)\\1'", &why));
    EXPECT_NE(why.find("bad regular expression"), std::string::npos) << why;
    why.clear();
    EXPECT_FALSE(eval("'a' =~ '\\5555555555555555555'", &why));
    EXPECT_EQ(why, "");
    EXPECT_LT(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10);
}

TEST(RibConditional, TheTakenBranchReachesTheTarget) {
    ribtest::ReadResult r = ribtest::readRib(R"RIB(Option "user" "string pass" ["beauty"]
FrameBegin 3
WorldBegin
IfBegin "$pass == 'shadow'"
  Sphere 1 -1 1 360
ElseIf "$Frame == 3"
  Sphere 2 -2 2 360
ElseIf "1"
  Sphere 3 -3 3 360
Else
  Sphere 4 -4 4 360
IfEnd
IfBegin "$pass == 'shadow'"
  Sphere 5 -5 5 360
Else
  Sphere 6 -6 6 360
IfEnd
WorldEnd
FrameEnd
)RIB");
    EXPECT_EQ(r.msgs, Lines{});
    EXPECT_EQ(spheres(r), (Lines{"2", "6"}));
    // (the conditionals themselves are not calls: option, frame, world, two spheres)
    EXPECT_EQ(r.target.calls.size(), 7u);
}

// A branch not taken is neither evaluated nor checked: a bad expression or a misplaced
// request there says nothing; an inner IfEnd still closes its own IfBegin.
TEST(RibConditional, NestedBranchesNotTakenAreNotEvaluated) {
    ribtest::ReadResult r = ribtest::readRib(R"RIB(WorldBegin
IfBegin "0"
  IfBegin "((("
    Format 1 1 1
  Else
    Sphere 1 -1 1 360
  IfEnd
  Sphere 2 -2 2 360
ElseIf "1"
  IfBegin "0"
    Sphere 3 -3 3 360
  Else
    Sphere 4 -4 4 360
  IfEnd
IfEnd
WorldEnd
)RIB");
    EXPECT_EQ(r.msgs, Lines{});
    EXPECT_EQ(spheres(r), Lines{"4"});
}

// An Attribute's value holds until its attribute block ends, over an Option's of the
// same name; any group is reachable as $group:name.
TEST(RibConditional, AttributeValuesFollowTheirBlocks) {
    ribtest::ReadResult r = ribtest::readRib(R"RIB(Option "user" "string side" ["option"]
WorldBegin
AttributeBegin
  Attribute "user" "string side" ["left"]
  Attribute "identifier" "string name" ["hero"]
  IfBegin "$side == 'left' && $identifier:name == 'hero'" Sphere 1 -1 1 360 IfEnd
  AttributeBegin
    Attribute "user" "string side" ["right"]
    IfBegin "$side == 'right'" Sphere 2 -2 2 360 IfEnd
  AttributeEnd
  IfBegin "$side == 'left'" Sphere 3 -3 3 360 IfEnd
AttributeEnd
IfBegin "$side == 'option' && !defined($identifier:name)" Sphere 4 -4 4 360 IfEnd
WorldEnd
)RIB");
    EXPECT_EQ(r.msgs, Lines{});
    EXPECT_EQ(spheres(r), (Lines{"1", "2", "3", "4"}));
}

TEST(RibConditional, MisplacedRequestsAndBadExpressionsAreReported) {
    ribtest::ReadResult r = ribtest::readRib(R"RIB(WorldBegin
ElseIf "1"
Else
IfEnd
IfBegin "1" Sphere 1 -1 1 360 Else Sphere 2 -2 2 360 Else Sphere 3 -3 3 360 IfEnd
IfBegin "$x ==" Sphere 4 -4 4 360 Else Sphere 5 -5 5 360 IfEnd
IfBegin 3 Sphere 6 -6 6 360 IfEnd
IfBegin "1"
WorldEnd
)RIB");
    EXPECT_EQ(
        r.msgs,
        (Lines{"t.rib:2: error: ElseIf without IfBegin",
               "t.rib:3: error: Else without IfBegin",
               "t.rib:4: error: IfEnd without IfBegin",
               "t.rib:5: error: Else after Else (IfBegin at t.rib:5)",
               "t.rib:6: error: condition \"$x ==\": a value expected at column 6 (taken "
               "as false)",
               "t.rib:7: error: IfBegin expects a string as argument 1",
               "t.rib:9: error: IfBegin at t.rib:8 never closed"}));
    EXPECT_EQ(spheres(r), (Lines{"1", "5"}));
}
