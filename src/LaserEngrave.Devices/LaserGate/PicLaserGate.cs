using System.Globalization;
using System.Text;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Wire.Serial;

namespace LaserEngrave.Devices.LaserGate;

/// <summary>The PIC that gates the laser's Q-switch, spoken to in ASCII lines (docs/laser-gate-protocol.md).</summary>
/// <remarks>
/// Every command string and the acknowledgement and error prefixes come from the <see cref="LaserGateProfile"/>.
/// Its <see cref="SerialChannel{TMessage}"/> reads the link and frames lines (ended by '\n', '\r' or both) with a
/// <see cref="LineFramer"/>. A command holds the line only while it is written: several may wait for their replies at
/// once (timed switching sends the switch-off while the switch-on's acknowledgement is still on its way), and each reply
/// line goes to the oldest command waiting that it answers. Each waits for its reply within the profile's timeout on the
/// given <see cref="System.TimeProvider"/>. After a timeout, ordinary commands wait while a keepalive gets the link back
/// in step; the emergency off's commands (<see cref="EmergencyAsync"/>) never do: they wait for nothing but the line being
/// written at that moment (GRBL's real-time commands bypass its queue the same way).
/// </remarks>
public sealed class PicLaserGate : ILaserGate, IAsyncDisposable
{
    private const int MaxLineLength = 1024;

    private readonly SerialChannel<string> _channel;
    private readonly TimeProvider _time;
    private readonly Lock _gate = new();
    private readonly AsyncLock _sendLock;

    // Ordinary commands in their order, held across a resynchronisation; the send lock is only held while a line is written.
    private readonly AsyncLock _order = new();
    private readonly List<(string Command, string Expected, TaskCompletionSource<string> Reply)> _pending = [];
    private bool _resynchronise;
    private bool _closed;

    // How many emergency commands were written: an ordinary command asked for before one is never written after it.
    private long _emergencies;

    // When the line of the command asked for last was written (LineWritten).
    private volatile Task<long?> _lineWritten = Task.FromResult<long?>(null);

    public PicLaserGate(ISerialLink link, LaserGateProfile profile, TimeProvider? timeProvider = null)
    {
        ArgumentNullException.ThrowIfNull(link);
        ArgumentNullException.ThrowIfNull(profile);
        Profile = profile;
        _time = timeProvider ?? TimeProvider.System;
        _channel = new SerialChannel<string>(link, new LineFramer(MaxLineLength), _time, OnLine, Close);
        _sendLock = _channel.SendLock;
        _channel.Start();
    }

    /// <summary>A line arrived while no command was waiting; raised on the reader loop.</summary>
    public event EventHandler<LaserGateLineEventArgs>? UnexpectedLine;

    public string PortName => _channel.Name;

    public LaserGateProfile Profile { get; }

    public TimeSpan Timeout => TimeSpan.FromMilliseconds(Profile.TimeoutMs);

    /// <inheritdoc/>
    public Task<long?> LineWritten => _lineWritten;

    /// <inheritdoc/>
    public bool IsReceiving => _channel.IsReceiving;

    public bool IsOpen
    {
        get
        {
            lock (_gate)
            {
                return !_closed;
            }
        }
    }

    /// <summary>Opens the port at the profile's baud rate (8N1, no handshake).</summary>
    public static PicLaserGate Open(string portName, LaserGateProfile profile, TimeProvider? timeProvider = null)
    {
        ArgumentNullException.ThrowIfNull(profile);
        var port = SerialPortLink.Open(new SerialPortSettings(portName) { BaudRate = profile.BaudRate });
        return new PicLaserGate(port, profile, timeProvider);
    }

    /// <summary>What a gate that does not identify itself (a frequency-only profile without an identify command, or one that never replies) is called.</summary>
    public const string UnidentifiedFrequencyOnly = "frequency-only gate (it does not identify itself)";

    public Task<string> IdentifyAsync(CancellationToken cancellationToken) =>
        Profile.Identifies ? SendAsync(Profile.IdentifyCommand, Profile.IdentifyReply, cancellationToken) : Task.FromResult(UnidentifiedFrequencyOnly);

    public async Task SetFrequencyAsync(int frequencyHz, CancellationToken cancellationToken)
    {
        ArgumentOutOfRangeException.ThrowIfNegative(frequencyHz);
        await SendAsync(Format(Profile.FrequencyCommand, frequencyHz), Format(Profile.FrequencyReply, frequencyHz), cancellationToken);
    }

    public async Task OffAsync(CancellationToken cancellationToken) =>
        await SendAsync(Profile.OffCommand, Profile.OffReply, cancellationToken);

    /// <summary>Asks for the state; the reply must read "STATE &lt;hz&gt; ON|OFF WDOG &lt;ms&gt; [TRIPPED]" after the acknowledgement prefix.</summary>
    public async Task<LaserGateState> GetStateAsync(CancellationToken cancellationToken)
    {
        ThrowIfFrequencyOnly(Profile.StatusCommand, "state to report");
        var text = await SendAsync(Profile.StatusCommand, Profile.StatusReply, cancellationToken);
        return ParseState(text) ?? throw new LaserGateException(
            PortName, Profile.StatusCommand, text, $"laser gate on {PortName}: cannot read the state from '{text}' (expected 'STATE <hz> ON|OFF WDOG <ms> [TRIPPED]')");
    }

    public async Task KeepAliveAsync(CancellationToken cancellationToken)
    {
        ThrowIfFrequencyOnly(Profile.KeepAliveCommand, "keepalive");
        await SendAsync(Profile.KeepAliveCommand, Profile.KeepAliveReply, cancellationToken);
    }

    public async Task SetWatchdogAsync(int milliseconds, CancellationToken cancellationToken)
    {
        ArgumentOutOfRangeException.ThrowIfNegative(milliseconds);
        if (!Profile.CountsBursts && milliseconds == 0)
        {
            // No watchdog is what this gate has already.
            return;
        }

        ThrowIfFrequencyOnly(Profile.WatchdogCommand, "watchdog");
        await SendAsync(Format(Profile.WatchdogCommand, milliseconds), Format(Profile.WatchdogReply, milliseconds), cancellationToken);
    }

    public async Task BurstAsync(int pulses, int frequencyHz, CancellationToken cancellationToken)
    {
        ArgumentOutOfRangeException.ThrowIfNegativeOrZero(pulses);
        ArgumentOutOfRangeException.ThrowIfNegativeOrZero(frequencyHz);
        ThrowIfFrequencyOnly(Profile.BurstCommand, "counted burst");
        await SendAsync(Format(Profile.BurstCommand, pulses, frequencyHz), Format(Profile.BurstReply, pulses, frequencyHz), cancellationToken);
    }

    /// <inheritdoc/>
    public async Task BurstAfterAsync(int pulses, int frequencyHz, int afterUs, CancellationToken cancellationToken)
    {
        ArgumentOutOfRangeException.ThrowIfNegativeOrZero(pulses);
        ArgumentOutOfRangeException.ThrowIfNegativeOrZero(frequencyHz);
        ArgumentOutOfRangeException.ThrowIfNegative(afterUs);
        ArgumentOutOfRangeException.ThrowIfGreaterThan(afterUs, MaxAfterUs);
        await SendAsync(Format(Profile.BurstAfterCommand, pulses, frequencyHz, afterUs), Format(Profile.BurstAfterReply, pulses, frequencyHz, afterUs), cancellationToken);
    }

    /// <summary>Longest delay of a scheduled burst the protocol allows, µs.</summary>
    public const int MaxAfterUs = 1_000_000;

    /// <inheritdoc/>
    /// <remarks>A gate that refuses the question (an older one answers CAPS? with its error prefix) has no capabilities; a timeout or a lost link still fails.</remarks>
    public async Task<IReadOnlySet<string>> GetCapabilitiesAsync(CancellationToken cancellationToken)
    {
        string text;
        try
        {
            text = await SendAsync(Profile.CapabilitiesCommand, Profile.CapabilitiesReply, cancellationToken);
        }
        catch (LaserGateException ex) when (ex.Reply.StartsWith(Profile.ErrorPrefix, StringComparison.Ordinal))
        {
            return new HashSet<string>(StringComparer.OrdinalIgnoreCase);
        }

        var words = text.Split(' ', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries);
        return new HashSet<string>(words.Skip(Profile.CapabilitiesReply.Split(' ', StringSplitOptions.RemoveEmptyEntries).Length), StringComparer.OrdinalIgnoreCase);
    }

    public async Task EmergencyAsync(EmergencyCommand command, CancellationToken cancellationToken)
    {
        var (line, expected) = command switch
        {
            EmergencyCommand.Off => (Profile.OffCommand, Profile.OffReply),
            EmergencyCommand.FrequencyZero => (Format(Profile.FrequencyCommand, 0), Format(Profile.FrequencyReply, 0)),
            EmergencyCommand.ShortestWatchdog => (Format(Profile.WatchdogCommand, MachineProfileValidator.MinWatchdogMs), Format(Profile.WatchdogReply, MachineProfileValidator.MinWatchdogMs)),
            _ => throw new ArgumentOutOfRangeException(nameof(command), command, "not a command of the emergency off"),
        };

        TaskCompletionSource<string> reply;
        var written = NewLineWritten();
        await _sendLock.WaitAsync(cancellationToken);
        try
        {
            lock (_gate)
            {
                _emergencies++;
            }

            reply = await WriteAsync(line, expected, written, cancellationToken);
        }
        finally
        {
            _sendLock.Release();
            written.TrySetResult(null);
        }

        await AwaitReplyAsync(line, reply, cancellationToken);
    }

    public ValueTask CloseAsync() => _channel.DisposeAsync();

    /// <summary>Sends one command line and waits for its reply line (any acknowledgement or refusal answers it).</summary>
    /// <returns>The reply after the acknowledgement prefix, trimmed ("PICGATE 1.2" for "OK PICGATE 1.2").</returns>
    /// <exception cref="LaserGateException">The gate answered with the error prefix, or with neither prefix.</exception>
    /// <exception cref="DeviceTimeoutException">No reply line within the profile's timeout.</exception>
    /// <exception cref="LinkLostException">The link closed.</exception>
    public Task<string> SendAsync(string command, CancellationToken cancellationToken) => SendAsync(command, string.Empty, cancellationToken);

    /// <summary>Sends one command line and waits for the reply that answers it.</summary>
    /// <param name="command">The line, without its terminator.</param>
    /// <param name="expected">
    /// What the acknowledgement says after the prefix (the reply "OK FREQ 1000" answers "FREQ 1000"), or its first words; empty:
    /// any. A refusal always answers. Any other line is reported as unexpected and ignored: a late reply to an earlier command
    /// never acknowledges this one.
    /// </param>
    /// <param name="cancellationToken">Cancels the wait.</param>
    public async Task<string> SendAsync(string command, string expected, CancellationToken cancellationToken)
    {
        ArgumentNullException.ThrowIfNull(command);
        ArgumentNullException.ThrowIfNull(expected);
        TaskCompletionSource<string> reply;
        long asked;
        lock (_gate)
        {
            asked = _emergencies;
        }

        var written = NewLineWritten();
        await _order.WaitAsync(cancellationToken);
        try
        {
            bool resynchronise;
            lock (_gate)
            {
                resynchronise = _resynchronise;
            }

            // A frequency-only gate has no keepalive to get back in step with; its replies are told apart by what they say.
            if (resynchronise && Profile.CountsBursts)
            {
                // After a timeout a late reply may still be on its way: a keepalive answered by its own reply proves the line is in step.
                try
                {
                    await AwaitReplyAsync(Profile.KeepAliveCommand, await WriteLineAsync(Profile.KeepAliveCommand, Profile.KeepAliveReply, asked, null, cancellationToken), cancellationToken);
                }
                catch (DeviceTimeoutException ex)
                {
                    throw new DeviceTimeoutException($"laser gate on {PortName} did not acknowledge '{command}': it did not answer the '{Profile.KeepAliveCommand}' sent first to get back in step within {Profile.TimeoutMs} ms", ex);
                }
                lock (_gate)
                {
                    _resynchronise = false;
                }
            }

            reply = await WriteLineAsync(command, expected, asked, written, cancellationToken);
        }
        finally
        {
            _order.Release();
            written.TrySetResult(null);
        }

        return await AwaitReplyAsync(command, reply, cancellationToken);
    }

    // Holds the send lock only while the line is written, so that an emergency command waits for nothing longer. A command
    // asked for before an emergency command was written is dropped (GRBL's reset flushes its queue the same way): a
    // switch-on held up behind a resynchronisation must never reach the gate after the emergency off.
    private async Task<TaskCompletionSource<string>> WriteLineAsync(string command, string expected, long asked, TaskCompletionSource<long?>? written, CancellationToken cancellationToken)
    {
        await _sendLock.WaitAsync(cancellationToken);
        try
        {
            lock (_gate)
            {
                if (_emergencies != asked)
                {
                    throw new DeviceException($"laser gate on {PortName}: '{command}' was not sent: the emergency off went first");
                }
            }

            return await WriteAsync(command, expected, written, cancellationToken);
        }
        finally
        {
            _sendLock.Release();
        }
    }

    // Asked for now: the command's LineWritten from here on.
    private TaskCompletionSource<long?> NewLineWritten()
    {
        var written = new TaskCompletionSource<long?>(TaskCreationOptions.RunContinuationsAsynchronously);
        _lineWritten = written.Task;
        return written;
    }

    // Caller holds the send lock: the command joins the ones waiting for a reply, then goes on the wire.
    private async Task<TaskCompletionSource<string>> WriteAsync(string command, string expected, TaskCompletionSource<long?>? written, CancellationToken cancellationToken)
    {
        var reply = new TaskCompletionSource<string>(TaskCreationOptions.RunContinuationsAsynchronously);
        lock (_gate)
        {
            if (_closed)
            {
                throw LinkLost(command, waiting: false);
            }

            if (!Profile.NeverReplies)
            {
                _pending.Add((command, expected, reply));
            }
        }

        if (Profile.NeverReplies)
        {
            // A gate that never replies (the profile says so): the command is carried out, as far as anyone can tell,
            // once written; nothing waits for an answer (callers never report such a gate's laser off as confirmed).
            var completed = await _channel.WriteAsync(Encoding.ASCII.GetBytes(command + Profile.LineTerminator), $"laser gate on {PortName}: cannot send '{command}'", cancellationToken);
            written?.TrySetResult(completed);
            reply.SetResult(string.Empty);
            return reply;
        }

        try
        {
            var completed = await _channel.WriteAsync(Encoding.ASCII.GetBytes(command + Profile.LineTerminator), $"laser gate on {PortName}: cannot send '{command}'", cancellationToken);
            written?.TrySetResult(completed);
        }
        catch
        {
            ClearPending(reply);
            throw;
        }

        return reply;
    }

    private async Task<string> AwaitReplyAsync(string command, TaskCompletionSource<string> reply, CancellationToken cancellationToken)
    {
        string line;
        try
        {
            line = await Signals.WaitAsync(reply, Timeout, _time, () => _channel.IsReceiving, cancellationToken);
        }
        catch (TimeoutException)
        {
            ClearPending(reply);
            lock (_gate)
            {
                _resynchronise = true;
            }

            throw new DeviceTimeoutException($"laser gate on {PortName} did not acknowledge '{command}' within {Profile.TimeoutMs} ms");
        }
        catch (OperationCanceledException)
        {
            ClearPending(reply);
            lock (_gate)
            {
                _resynchronise = true;
            }

            throw;
        }

        // A gate that never replies has nothing to interpret: written is all anyone can know.
        return Profile.NeverReplies ? string.Empty : Interpret(command, line);
    }

    // Whether the line answers the command waiting: a refusal, an acknowledgement that says what is expected, or any line that is neither.
    private bool Answers(string line, string expected)
    {
        if ((Profile.ErrorPrefix.Length > 0 && line.StartsWith(Profile.ErrorPrefix, StringComparison.Ordinal)) || !line.StartsWith(Profile.AckPrefix, StringComparison.Ordinal))
        {
            return true;
        }

        // A bare acknowledgement says nothing to match, so it answers whatever waits.
        var body = line[Profile.AckPrefix.Length..].Trim();
        return expected.Length == 0 || body.Length == 0
            || body.Equals(expected, StringComparison.OrdinalIgnoreCase)
            || body.StartsWith(expected + " ", StringComparison.OrdinalIgnoreCase);
    }

    public ValueTask DisposeAsync() => _channel.DisposeAsync();

    /// <summary>Reads "STATE 1000 ON WDOG 1000 [TRIPPED]"; null when the text has another shape.</summary>
    internal static LaserGateState? ParseState(string text)
    {
        var words = text.Split(' ', StringSplitOptions.RemoveEmptyEntries | StringSplitOptions.TrimEntries);
        if (words.Length is < 5 or > 6
            || !words[0].Equals("STATE", StringComparison.OrdinalIgnoreCase)
            || !int.TryParse(words[1], NumberStyles.None, CultureInfo.InvariantCulture, out var hz)
            || !words[3].Equals("WDOG", StringComparison.OrdinalIgnoreCase)
            || !int.TryParse(words[4], NumberStyles.None, CultureInfo.InvariantCulture, out var watchdogMs))
        {
            return null;
        }

        bool firing;
        if (words[2].Equals("ON", StringComparison.OrdinalIgnoreCase))
        {
            firing = true;
        }
        else if (words[2].Equals("OFF", StringComparison.OrdinalIgnoreCase))
        {
            firing = false;
        }
        else
        {
            return null;
        }

        var tripped = words.Length == 6;
        if (tripped && !words[5].Equals("TRIPPED", StringComparison.OrdinalIgnoreCase))
        {
            return null;
        }

        return new LaserGateState(hz, firing, watchdogMs, tripped);
    }

    // A frequency-only gate knows FREQ and its off only: anything else would be answered as unknown (or not at all).
    private void ThrowIfFrequencyOnly(string command, string what)
    {
        if (!Profile.CountsBursts)
        {
            throw new LaserGateException(PortName, command, string.Empty, $"laser gate on {PortName} is a frequency-only gate (the profile's gate.kind): it has no {what}");
        }
    }

    private static string Format(string format, params object[] values) => string.Format(CultureInfo.InvariantCulture, format, values);

    private string Interpret(string command, string line)
    {
        // The error prefix is checked first so that a profile whose prefixes overlap still sees refusals.
        if (Profile.ErrorPrefix.Length > 0 && line.StartsWith(Profile.ErrorPrefix, StringComparison.Ordinal))
        {
            throw new LaserGateException(PortName, command, line, $"laser gate on {PortName} refused '{command}': {line}");
        }

        if (line.StartsWith(Profile.AckPrefix, StringComparison.Ordinal))
        {
            return line[Profile.AckPrefix.Length..].Trim();
        }

        throw new LaserGateException(
            PortName, command, line, $"laser gate on {PortName} answered '{command}' with '{line}' (expected '{Profile.AckPrefix}' or '{Profile.ErrorPrefix}')");
    }

    private void ClearPending(TaskCompletionSource<string> reply)
    {
        lock (_gate)
        {
            _pending.RemoveAll(p => p.Reply == reply);
        }
    }

    private LinkLostException LinkLost(string command, bool waiting)
    {
        var what = _channel.ClosedState;
        return _channel.LinkLost(waiting
            ? $"laser gate on {PortName}: {what} while waiting for the reply to '{command}'"
            : $"laser gate on {PortName}: cannot send '{command}': {what}");
    }

    private void OnLine(string line)
    {
        TaskCompletionSource<string>? waiter = null;
        lock (_gate)
        {
            var index = _pending.FindIndex(p => Answers(line, p.Expected));
            if (index >= 0)
            {
                waiter = _pending[index].Reply;
                _pending.RemoveAt(index);
            }
        }

        if (waiter is not null)
        {
            waiter.TrySetResult(line);
        }
        else
        {
            UnexpectedLine?.Invoke(this, new LaserGateLineEventArgs(line));
        }
    }

    private void Close(Exception? reason)
    {
        List<(TaskCompletionSource<string> Reply, LinkLostException Error)> failed;
        lock (_gate)
        {
            if (_closed)
            {
                return;
            }

            _closed = true;
            failed = [.. _pending.Select(p => (p.Reply, LinkLost(p.Command, waiting: true)))];
            _pending.Clear();
        }

        foreach (var (reply, error) in failed)
        {
            reply.TrySetException(error);
        }
    }
}
