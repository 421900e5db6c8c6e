using System.Globalization;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Devices.Execution;
using LaserEngrave.Simulator.Burn;
using Microsoft.Extensions.DependencyInjection;
using OpenQA.Selenium;

namespace LaserEngrave.App.Tests.Web;

/// <summary>
/// The laser's cross during a run against the simulator's own stage: the app's simulator as the user has it (the
/// front ends' twin at the machine's pace), so a row takes its real seconds and the page draws the cross many times in it.
/// </summary>
/// <remarks>
/// No wall-clock luck: the page keeps, beside each cross it draws, the instant on the machine's clock that cross is
/// for, and the twin's trajectory is asked at that instant.
/// </remarks>
public sealed class CrossBrowserTests : BrowserTest
{
    /// <summary>How far the cross may be from the stage it stands for (issue 36: 0.2 mm at 1 mm/s).</summary>
    private const double ToleranceMm = 0.2;

    protected override void AddServices(IServiceCollection services) =>
        services.AddSingleton<IMachineConnectionFactory>(new MachineConnectionFactory(MachineConnectionFactory.DefaultSimulatorOptions));

    [Fact]
    public void Run_QrAtOneMmPerSecond_TheCrossFollowsTheTwinsStageWithinTwoTenthsOfAMillimetre()
    {
        Size1280x720();
        OpenSample("qr-code.bmp");
        SetField("widthMm", "10");
        SetField("burnSpeedMmPerS", "1");
        WaitFor(_ => Math.Abs(FieldValue("widthMm") - 10) < 1e-9 && Math.Abs(FieldValue("burnSpeedMmPerS") - 1) < 1e-9, "10 mm wide at 1 mm/s");
        Id("connect").Click();
        WaitFor(_ => Enabled("start"), "connected to the simulator");
        ZoomAround(FieldValue("originXMm") + 5, FieldValue("originYMm") + 5, 6);

        var main = Host.Services.GetRequiredService<MainViewModel>();
        var connection = main.Machine.Connection!;
        var twin = ((BurnInspector)connection.Inspector!).Machine;
        var microstepMm = (X: main.Machine.Profile.X.MicrostepUm / 1000, Y: main.Machine.Profile.Y.MicrostepUm / 1000);

        // The twin counts seconds from its start; the page's instants are the machine clock's timestamps. Read together,
        // until no event moved the clock between the two readings.
        double origin;
        double before, after;
        do
        {
            before = connection.TimeProvider.GetTimestamp() / (double)connection.TimeProvider.TimestampFrequency;
            origin = before - twin.NowSeconds;
            after = connection.TimeProvider.GetTimestamp() / (double)connection.TimeProvider.TimestampFrequency;
        }
        while (before != after);

        Id("start").Click();
        WaitFor(_ => main.Run.Progress is { State: RunState.Running, Run.RunsDone: > 0 }, "the first row burning", 60);

        // Every cross the page draws for the next 12 s of rows (a row is about 11 s), each with the twin's stage then.
        var samples = new List<(double At, double CrossX, double CrossY, double StageX, double StageY, bool InRow)>();
        var seen = new HashSet<string>();
        var until = DateTime.UtcNow.AddSeconds(12);
        while (DateTime.UtcNow < until && main.Run.Progress?.State == RunState.Running)
        {
            var drawn = Id("stage-host").GetAttribute("data-laser-drawn");
            if (drawn is null || !seen.Add(drawn))
            {
                continue;
            }

            var v = drawn.Split(',');
            if (v[5].Length == 0)
            {
                continue;
            }

            var n = v.Take(6).Select(p => double.Parse(p, CultureInfo.InvariantCulture)).ToArray();
            var at = n[5] - origin;
            var (scale, ox, oy) = (n[2], n[3], n[4]);

            // In a row: the stage moving along X only (a turn at the row's end moves Y).
            var straight = Math.Abs(twin.Recorder.Y.VelocityAt(at)) < 1e-9;
            samples.Add((at, (n[0] - ox) / scale, (n[1] - oy) / scale, twin.Recorder.X.PositionAt(at) * microstepMm.X, twin.Recorder.Y.PositionAt(at) * microstepMm.Y, straight));
        }

        Id("abort").Click();
        WaitFor(d => d.FindElement(By.Id("status-run")).Text == "aborted", "aborted", 60);

        var distances = samples.Select(s => (s.At, s.InRow, Mm: Math.Sqrt(Math.Pow(s.CrossX - s.StageX, 2) + Math.Pow(s.CrossY - s.StageY, 2)))).ToList();
        var inRow = distances.Where(d => d.InRow).ToList();
        var worst = inRow.MaxBy(d => d.Mm);
        var table = string.Join(Environment.NewLine, samples.Select(s => string.Create(CultureInfo.InvariantCulture,
            $"{s.At:0.000} s cross {s.CrossX:0.000},{s.CrossY:0.000} stage {s.StageX:0.000},{s.StageY:0.000}{(s.InRow ? "" : " (turn)")}")));
        TestContext.Current.TestOutputHelper?.WriteLine(string.Create(CultureInfo.InvariantCulture,
            $"{samples.Count} crosses, {inRow.Count} in rows; worst in a row {worst.Mm:0.000} mm at {worst.At:0.000} s; worst overall {distances.Max(d => d.Mm):0.000} mm"));
        TestContext.Current.TestOutputHelper?.WriteLine(table);
        Assert.True(inRow.Count >= 50, $"only {inRow.Count} crosses drawn in rows");
        Assert.True(worst.Mm <= ToleranceMm, string.Create(CultureInfo.InvariantCulture, $"the cross was {worst.Mm:0.000} mm from the stage at {worst.At:0.000} s in a row"));

        // The turns between rows too: the travel is the engine's as well.
        var worstAll = distances.MaxBy(d => d.Mm);
        Assert.True(worstAll.Mm <= ToleranceMm, string.Create(CultureInfo.InvariantCulture, $"the cross was {worstAll.Mm:0.000} mm from the stage at {worstAll.At:0.000} s"));
    }
}
