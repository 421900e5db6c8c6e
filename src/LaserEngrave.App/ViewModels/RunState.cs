namespace LaserEngrave.App.ViewModels;

/// <summary>Where a run is in its life.</summary>
public enum RunState
{
    Idle,
    Running,
    Paused,
    Aborting,
    Completed,
    Aborted,
    Failed,
}
