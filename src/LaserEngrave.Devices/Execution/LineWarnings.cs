using System.Globalization;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// What the stage's line dropped while a run was under way (an unfinished frame after a proven gap), for the run's log:
/// a reply dropped is a reply its request waits for in vain, and without this the log would only say that it timed out.
/// </summary>
internal sealed class LineWarnings : IDisposable
{
    private readonly Lock _sync = new();
    private readonly List<string> _warnings = [];
    private readonly ZaberConnection? _connection;
    private readonly TimeProvider _time;
    private readonly long _start;
    private int _more;

    /// <param name="stage">The run's stage; only a Zaber chain's line is watched.</param>
    /// <param name="time">The run's clock: each line says when, as seconds since the run began.</param>
    public LineWarnings(IStage stage, TimeProvider time)
    {
        _time = time;
        _start = time.GetTimestamp();
        _connection = (stage as ZaberChain)?.Connection;
        if (_connection is not null)
        {
            _connection.LineEvent += OnLineEvent;
        }
    }

    /// <summary>The lines so far (the last counts those past <see cref="RunRecord.MaxLineWarnings"/>); null when none.</summary>
    public IReadOnlyList<string>? Lines
    {
        get
        {
            lock (_sync)
            {
                if (_warnings.Count == 0)
                {
                    return null;
                }

                return _more == 0 ? [.. _warnings] : [.. _warnings, string.Create(CultureInfo.InvariantCulture, $"{_more} more of the same kind")];
            }
        }
    }

    public void Dispose()
    {
        if (_connection is not null)
        {
            _connection.LineEvent -= OnLineEvent;
        }
    }

    // Raised on the reader loop: only noted here.
    private void OnLineEvent(object? sender, ZaberLineEventArgs e)
    {
        if (e.Kind != ZaberLineEvent.PartialFrameDropped)
        {
            return;
        }

        var line = string.Create(CultureInfo.InvariantCulture, $"{_time.GetElapsedTime(_start).TotalSeconds:0.000} s: {e.Message}");
        lock (_sync)
        {
            if (_warnings.Count < RunRecord.MaxLineWarnings - 1)
            {
                _warnings.Add(line);
            }
            else
            {
                _more++;
            }
        }
    }
}
