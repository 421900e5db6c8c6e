using LaserEngrave.Core.Logging;

namespace LaserEngrave.Simulator.Burn;

/// <summary>
/// What the twin knows of the sample, as a front end asks for it: each run's burn check for the log
/// (<see cref="IRunInspector"/>), the last check's reports, and the pulse map of any window of its time.
/// </summary>
public interface ITwinInspector : IRunInspector
{
    /// <summary>The last drawing check's report; null before the first.</summary>
    PathReport? PathReport { get; }

    /// <summary>The last check's whole report (the burned image, the pulse map); null before the first.</summary>
    BurnReport? Report { get; }

    /// <summary>Seconds since the twin started, on its clock (the time base of <see cref="AnalyzeSince"/>).</summary>
    double NowSeconds { get; }

    /// <summary>Everything the twin burned on <paramref name="grid"/> since <paramref name="startSeconds"/> (e.g. a whole sweep's pulse map).</summary>
    BurnReport AnalyzeSince(BurnGrid grid, double startSeconds);
}
