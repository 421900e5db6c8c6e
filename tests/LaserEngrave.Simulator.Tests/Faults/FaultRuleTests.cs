using LaserEngrave.Simulator.Faults;

namespace LaserEngrave.Simulator.Tests.Faults;

public class FaultRuleTests
{
    [Fact]
    public void ParseRules_TheBriefsExamples_ParseToTheirKinds()
    {
        var rules = FaultInjector.ParseRules(
            "drop-reply:stage:after=10, corrupt:stage:after=5,delay:stage:ms=500,error:stage:code=20:after=3,silent:stage:after=50,disconnect:stage:after=20,no-ack:gate:after=4");

        Assert.Equal(
            [FaultKind.DropReply, FaultKind.Corrupt, FaultKind.Delay, FaultKind.Error, FaultKind.Silent, FaultKind.Disconnect, FaultKind.NoAck],
            rules.Select(r => r.Kind));
        Assert.Equal(new FaultRule(FaultKind.Error, FaultTarget.Stage) { Code = 20, After = 3 }, rules[3]);
        Assert.Equal(new FaultRule(FaultKind.NoAck, FaultTarget.Gate) { After = 4 }, rules[6]);
    }

    [Fact]
    public void Parse_AllKeys_AreRead()
    {
        var rule = FaultRule.Parse("corrupt:stage:device=2:after=7:count=3:byte=4");

        Assert.Equal(new FaultRule(FaultKind.Corrupt, FaultTarget.Stage) { Device = 2, After = 7, Count = 3, ByteIndex = 4 }, rule);
    }

    [Fact]
    public void Parse_CountAll_IsUnlimited()
    {
        Assert.Equal(int.MaxValue, FaultRule.Parse("drop-reply:gate:count=all").EffectiveCount);
    }

    [Theory]
    [InlineData("drop-reply:stage", 1)]
    [InlineData("silent:stage", int.MaxValue)]
    [InlineData("no-ack:gate", int.MaxValue)]
    [InlineData("disconnect:gate", 1)]
    public void EffectiveCount_Default_DependsOnTheKind(string spec, int count)
    {
        Assert.Equal(count, FaultRule.Parse(spec).EffectiveCount);
    }

    [Theory]
    [InlineData("error:stage", 255)]
    [InlineData("error:gate", 1)]
    [InlineData("error:laser:code=9", 9)]
    public void EffectiveCode_DefaultsPerTarget(string spec, int code)
    {
        Assert.Equal(code, FaultRule.Parse(spec).EffectiveCode);
    }

    [Theory]
    [InlineData("drop-reply:stage:after=10")]
    [InlineData("corrupt:stage:device=1:count=all:byte=0")]
    [InlineData("delay:stage:device=1:command=60:after=9:ms=150")]
    [InlineData("delay:gate:after=2:ms=1500")]
    [InlineData("error:stage:code=20")]
    [InlineData("no-ack:gate:after=4")]
    public void ToString_ParsesBackToTheSameRule(string spec)
    {
        var rule = FaultRule.Parse(spec);

        Assert.Equal(rule, FaultRule.Parse(rule.ToString()));
    }

    [Theory]
    [InlineData("explode:stage", "unknown kind")]
    [InlineData("drop-reply:camera", "unknown target")]
    [InlineData("drop-reply", "expected kind:target")]
    [InlineData("delay:stage:ms=-5", "ms=-5")]
    [InlineData("drop-reply:stage:after=x", "after=x")]
    [InlineData("drop-reply:stage:ms=5", "'ms' does not apply")]
    [InlineData("error:gate:device=1", "'device' does not apply")]
    [InlineData("delay:gate:command=60", "'command' does not apply")]
    [InlineData("delay:stage:command=256", "command=256 is not a whole number in 0..255")]
    [InlineData("no-ack:stage", "gate only")]
    [InlineData("silent:stage:count=2", "takes no count")]
    [InlineData("drop-reply:stage:after", "not key=value")]
    public void Parse_Bad_ThrowsFormatExceptionNamingTheProblem(string spec, string why)
    {
        var ex = Assert.Throws<FormatException>(() => FaultInjector.ParseRules(spec));

        Assert.Contains(why, ex.Message, StringComparison.Ordinal);
        Assert.Contains(spec, ex.Message, StringComparison.Ordinal);
    }

    [Theory]
    [InlineData(null)]
    [InlineData("")]
    [InlineData("  ")]
    public void ParseRules_Empty_IsNoRules(string? spec)
    {
        Assert.Empty(FaultInjector.ParseRules(spec));
    }
}
