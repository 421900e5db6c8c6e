namespace LaserEngrave.Devices.Execution;

/// <summary>The motion strategies of a run, one per kind of plan: what the engine runs and what preflight checks the firmware for.</summary>
internal enum RunMotion
{
    /// <summary>Each move awaits its reply before the next (a paper plan, or one without a timing model).</summary>
    StepByStep,

    /// <summary>Strokes and travels sent at times computed in advance, the laser switched by time.</summary>
    Timed,

    /// <summary>Stop at each dot and fire a counted burst.</summary>
    Dots,

    /// <summary>A drawing's strokes, each axis streaming its speed.</summary>
    Strokes,
}
