namespace LaserEngrave.Devices.Execution;

/// <summary>A snapshot of an <see cref="EngraveSession"/>: its state, the pass under way, and that pass's executor progress.</summary>
/// <param name="State">The session's state: the pass's executor's, except that a pass's end is not the session's until the last pass.</param>
/// <param name="Pass">The pass under way, from 1.</param>
/// <param name="Passes">The passes this session runs.</param>
/// <param name="MovesDone">Moves of the plan completed in this pass (with those done before a resume).</param>
/// <param name="MovesTotal">Moves of the plan.</param>
/// <param name="PauseRequested">A pause was asked and not yet resumed (it takes effect after the current move).</param>
/// <param name="Run">The pass's executor progress: rows, runs, percent and time left of this pass, position, laser.</param>
/// <param name="Layer">The layer under way, from 1 (a job of layers; 1 for a single job).</param>
/// <param name="Recoveries">The timing doubts the session has gone on from so far (<see cref="EngraveSession.MaxRecoveries"/>).</param>
/// <param name="LayerPass">The pass under way within its layer, from 1 (a single job: <paramref name="Pass"/>).</param>
/// <param name="LayerPasses">The passes of the layer under way (a single job: <paramref name="Passes"/>); a job of layers counts its layers apart.</param>
/// <param name="Recovering">
/// The pass under way is going on from its stop point after a timing doubt, and has not yet started moving again (its
/// preflight is the recovery's, not a new pass's or layer's).
/// </param>
public sealed record EngraveProgress(RunState State, int Pass, int Passes, long MovesDone, long MovesTotal, bool PauseRequested, RunProgress Run, int Layer = 1, int Recoveries = 0, bool Recovering = false, int LayerPass = 0, int LayerPasses = 0)
{
    /// <summary>The pass within its layer as a person counts it ("pass 2 of 3"): the layer's when known, else the session's.</summary>
    public (int Pass, int Passes) PassInLayer => LayerPasses > 0 ? (LayerPass, LayerPasses) : (Pass, Passes);

    /// <summary>Share of all passes done, 0..1.</summary>
    public double Fraction => MovesTotal > 0 ? Math.Clamp((Pass - 1 + ((double)MovesDone / MovesTotal)) / Math.Max(1, Passes), 0, 1) : 0;
}
