using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Planning;

/// <summary>
/// The device-unit program of one part's pass: its motion data, converted once from the process, and its steps
/// (absolute microsteps, speed data, timed laser edges), which the estimate interprets and the executor sends.
/// </summary>
/// <remarks>Closed: the kinds of program are Core's own, so a <c>switch</c> over them is exhaustive.</remarks>
public abstract class PartProgram
{
    private protected PartProgram(ProcessSettings process, PlanStrategy strategy, double microstepUm, LaserGateProfile gate)
    {
        ArgumentNullException.ThrowIfNull(process);
        ArgumentNullException.ThrowIfNull(gate);
        Process = process;
        Strategy = strategy;
        MicrostepUm = microstepUm;
        Gate = gate;
        Motion = MotionData.Of(process, strategy, microstepUm);
    }

    /// <summary>The process the program was converted from.</summary>
    public ProcessSettings Process { get; }

    public PlanStrategy Strategy { get; }

    public double MicrostepUm { get; }

    /// <summary>The gate's command strings (their lengths time the laser's switchings).</summary>
    public LaserGateProfile Gate { get; }

    /// <summary>Burn and travel speed data and acceleration data.</summary>
    public MotionData Motion { get; }

    /// <summary>The model a run of it switches the laser by time with (a timed raster's, a drawing's); null for dots and step by step.</summary>
    public virtual TimedSwitching? SwitchTiming => null;
}
